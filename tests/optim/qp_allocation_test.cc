// Zero heap allocations per cycle: after the first solve at a given size, 1,000 warm re-solves of
// a 40-knot body-planner-shaped QP (bounds and linear terms updated each cycle) allocate nothing;
// cold re-solves neither; nor do the banded interior point's solves, along both of its paths: the
// warm start's polish of the last active set, and the interior point when that polish fails or
// the warm start is off.
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/banded_ipm_qp_solver.h"
#include "stairplan/optim/body_qp_example.h"

using namespace stairplan::optim;
using stairplan::testing::AllocationScope;

namespace {

struct CycleCounts {
  std::size_t allocations = 0;
  int solved = 0, iterations = 0;
  int warm_polished = 0;  // banded-ipm: solves ended by the polish of the last active set alone
};

// After one warm-up solve, `cycles` cycles of the example's update and a solve, counted; with
// `rewrite_matrix` A also counts as rewritten every other cycle (as the body planner's rows
// are), so that whatever a solver keeps of A is made again; with `hold` the example is not
// updated (the same program each cycle: its active set holds).
CycleCounts SolveCycles(Solver& solver, int cycles, bool rewrite_matrix = false, bool hold = false) {
  BodyQpExample e = MakeBodyQpExample(40);
  SolveResult result;
  solver.Solve(e.program, &result);  // warm-up: sizes the workspace and the result
  REQUIRE(result.status == SolveStatus::kSolved);
  CycleCounts counts;
  AllocationScope scope;
  for (int cycle = 1; cycle <= cycles; ++cycle) {
    if (!hold) UpdateBodyQpExample(cycle, &e);
    if (rewrite_matrix && cycle % 2 == 0) e.program.MutableConstraintMatrix();
    solver.Solve(e.program, &result);
    counts.solved += result.status == SolveStatus::kSolved ? 1 : 0;
    counts.iterations += result.info.iterations;
    if (const auto* ipm = dynamic_cast<const BandedIpmQpSolver*>(&solver)) counts.warm_polished += ipm->warm_started();
  }
  counts.allocations = scope.count();
  return counts;
}

}  // namespace

TEST_CASE("1,000 warm re-solves of a 40-knot body QP allocate nothing", "[allocation]") {
  ActiveSetQpSolver solver;
  const CycleCounts counts = SolveCycles(solver, 1000);
  CHECK(counts.allocations == 0);
  CHECK(counts.solved == 1000);
  CHECK(counts.iterations > 0);  // the active set really changed along the way
}

TEST_CASE("cold re-solves allocate nothing either", "[allocation]") {
  ActiveSetQpSettings settings;
  settings.warm_start = false;
  ActiveSetQpSolver solver(settings);
  const CycleCounts counts = SolveCycles(solver, 100);
  CHECK(counts.allocations == 0);
  CHECK(counts.solved == 100);
}

TEST_CASE("banded interior-point solves of a same-shaped program allocate nothing", "[allocation]") {
  // The warm start (the default) along the example's cycles: its active set changes every cycle,
  // so each solve is a failed polish and then the interior point.
  BandedIpmQpSolver solver;
  const CycleCounts counts = SolveCycles(solver, 100, true);
  CHECK(counts.allocations == 0);
  CHECK(counts.solved == 100);
  CHECK(counts.iterations >= 3 * (100 - counts.warm_polished));  // the others iterated
  CHECK(counts.warm_polished < 100);
  // The same program each cycle: the polish of the last active set holds, and solves alone.
  BandedIpmQpSolver held;
  const CycleCounts held_counts = SolveCycles(held, 100, true, true);
  CHECK(held_counts.allocations == 0);
  CHECK(held_counts.solved == 100);
  CHECK(held_counts.warm_polished == 100);
  CHECK(held_counts.iterations == 0);
  // Without the warm start every solve runs the interior point.
  BandedIpmQpSettings settings;
  settings.warm_start = false;
  BandedIpmQpSolver cold(settings);
  const CycleCounts cold_counts = SolveCycles(cold, 100, true);
  CHECK(cold_counts.allocations == 0);
  CHECK(cold_counts.solved == 100);
  CHECK(cold_counts.warm_polished == 0);
  CHECK(cold_counts.iterations >= 100 * 3);  // every solve iterates (a few times: not a shortcut)
}
