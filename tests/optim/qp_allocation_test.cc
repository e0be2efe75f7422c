// Zero heap allocations per cycle: after the first solve at a given size, 1,000 warm re-solves of
// a 40-knot body-planner-shaped QP (bounds and linear terms updated each cycle) allocate nothing;
// cold re-solves neither; nor do the banded interior point's solves (every one cold).
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/banded_ipm_qp_solver.h"
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

TEST_CASE("banded interior-point solves of a same-shaped program allocate nothing", "[allocation]") {
  BodyQpExample e = MakeBodyQpExample(40);
  BandedIpmQpSolver solver;
  SolveResult result;
  solver.Solve(e.program, &result);  // warm-up: sizes the workspace, orders the variables
  REQUIRE(result.status == SolveStatus::kSolved);
  std::size_t allocations = 0;
  int solved = 0, iterations = 0;
  {
    AllocationScope scope;
    for (int cycle = 1; cycle <= 100; ++cycle) {
      UpdateBodyQpExample(cycle, &e);
      // Every other cycle A counts as rewritten (as the body planner's rows are): the copy of A
      // and the variable order are made again, in the storage they had.
      if (cycle % 2 == 0) e.program.MutableConstraintMatrix();
      solver.Solve(e.program, &result);
      solved += result.status == SolveStatus::kSolved ? 1 : 0;
      iterations += result.info.iterations;
    }
    allocations = scope.count();
  }
  CHECK(allocations == 0);
  CHECK(solved == 100);
  CHECK(iterations > 100);  // real interior-point solves, not a shortcut
}
