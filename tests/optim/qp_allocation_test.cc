// Zero heap allocations per cycle: after the first solve at a given size, 1,000 warm re-solves of
// a 40-knot body-planner-shaped QP (bounds and linear terms updated each cycle) allocate nothing;
// cold re-solves neither.
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/body_qp_example.h"

using namespace stairplan::optim;
using stairplan::testing::AllocationScope;

TEST_CASE("1,000 warm re-solves of a 40-knot body QP allocate nothing", "[allocation]") {
  BodyQpExample e = MakeBodyQpExample(40);
  ActiveSetQpSolver solver;
  SolveResult result;
  solver.Solve(e.program, &result);  // warm-up: sizes the workspace and the result
  REQUIRE(result.status == SolveStatus::kSolved);
  int solved = 0, iterations = 0;
  std::size_t allocations = 0;
  {
    AllocationScope scope;
    for (int cycle = 1; cycle <= 1000; ++cycle) {
      UpdateBodyQpExample(cycle, &e);
      solver.Solve(e.program, &result);
      solved += result.status == SolveStatus::kSolved ? 1 : 0;
      iterations += result.info.iterations;
    }
    allocations = scope.count();
  }
  CHECK(allocations == 0);
  CHECK(solved == 1000);
  CHECK(iterations > 0);  // the active set really changed along the way
}

TEST_CASE("cold re-solves allocate nothing either", "[allocation]") {
  BodyQpExample e = MakeBodyQpExample(40);
  ActiveSetQpSettings settings;
  settings.warm_start = false;
  ActiveSetQpSolver solver(settings);
  SolveResult result;
  solver.Solve(e.program, &result);
  std::size_t allocations = 0;
  int solved = 0;
  {
    AllocationScope scope;
    for (int cycle = 1; cycle <= 100; ++cycle) {
      UpdateBodyQpExample(cycle, &e);
      solver.Solve(e.program, &result);
      solved += result.status == SolveStatus::kSolved ? 1 : 0;
    }
    allocations = scope.count();
  }
  CHECK(allocations == 0);
  CHECK(solved == 100);
}
