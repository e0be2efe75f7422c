// ClpSolver: CLP reaches the published optima of a few Maros-Meszaros QPs with duals that satisfy
// the KKT conditions (qpbenchmark's residuals), reports an infeasible QP as infeasible, and its
// warm start (the kept basis) re-solves a changed problem to the cold solution.
#include <catch2/catch.hpp>

#include <string>

#include "stairplan/solvers/clp_solver.h"
#include "stairplan/optim/qp_residuals.h"
#include "stairplan/optim/qps_reader.h"
#include "test_paths.h"

using namespace stairplan::optim;
using stairplan::testing::SharedPath;

namespace {

// min 0.5 |x|^2 - x1 s.t. x1 + x2 >= `rhs`, x <= 4 (both).
Program ClpTinyQp(double rhs) {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  p.AddQuadraticCost(x, Eigen::Matrix2d::Identity(), Eigen::Vector2d(-1.0, 0.0));
  p.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 1.0)}}, Eigen::VectorXd::Constant(1, rhs),
                        Eigen::VectorXd::Constant(1, kInf), "sum");
  p.SetVariableBounds(x, Eigen::Vector2d::Constant(-kInf), Eigen::Vector2d::Constant(4.0));
  return p;
}

}  // namespace

TEST_CASE("CLP reaches the published optima of Maros-Meszaros QPs with KKT-consistent duals", "[clp]") {
  if (!ClpSolver::IsAvailable()) {
    WARN("CLP tests skipped: built without coinor-libclp-dev");
    return;
  }
  const std::string dir = SharedPath("data/qp/maros_meszaros");
  if (dir.empty()) {
    WARN("CLP Maros-Meszaros test skipped: ../shared not found");
    return;
  }
  struct Known {
    const char* name;
    double optimum;  // INDEX.tsv
  };
  for (const Known& k : {Known{"HS21", -9.9960000e+01}, Known{"HS35", 1.1111111e-01}, Known{"QPTEST", 4.3718750e+00},
                         Known{"DUAL4", 7.4609084e-01}, Known{"QAFIRO", -1.5907818e+00}}) {
    const QpsProblem q = ReadQpsFile(dir + "/" + k.name + ".SIF");
    for (const ClpAlgorithm algorithm : {ClpAlgorithm::kPrimalSimplex, ClpAlgorithm::kBarrier}) {
      ClpSettings settings;
      settings.algorithm = algorithm;
      ClpSolver clp(settings);
      const SolveResult r = clp.Solve(q.program);
      INFO(k.name << " with " << clp.name());
      REQUIRE(r.status == SolveStatus::kSolved);
      CHECK(r.objective == Approx(k.optimum).epsilon(1e-7));
      const QpResiduals residuals = ComputeQpResiduals(q.program, r);
      CHECK(residuals.Within(1e-6));
    }
  }
}

TEST_CASE("CLP reports an infeasible QP as infeasible, and its warm start re-solves to the cold answer", "[clp]") {
  if (!ClpSolver::IsAvailable()) {
    WARN("CLP tests skipped: built without coinor-libclp-dev");
    return;
  }
  ClpSolver clp;
  CHECK(clp.Solve(ClpTinyQp(9.0)).status == SolveStatus::kInfeasible);  // x1 + x2 <= 8 < 9
  Program p = ClpTinyQp(1.0);
  const SolveResult first = clp.Solve(p);
  REQUIRE(first.status == SolveStatus::kSolved);
  CHECK(first.x[0] == Approx(1.0).margin(1e-9));  // the row is inactive at the unconstrained minimum
  // Move the row to x1 + x2 >= 3: x = (2, 1), dual of the row -1 (active lower side).
  p.SetConstraintBounds({"sum", 0, 1}, Eigen::VectorXd::Constant(1, 3.0), Eigen::VectorXd::Constant(1, kInf));
  const SolveResult warm = clp.Solve(p);
  ClpSolver fresh;
  const SolveResult cold = fresh.Solve(p);
  REQUIRE(warm.status == SolveStatus::kSolved);
  REQUIRE(cold.status == SolveStatus::kSolved);
  CHECK((warm.x - cold.x).lpNorm<Eigen::Infinity>() < 1e-9);
  CHECK(warm.x[0] == Approx(2.0).margin(1e-9));
  CHECK(warm.row_duals[0] == Approx(-1.0).margin(1e-9));
  CHECK(warm.active_set.rows[0] == -1);
  CHECK(ComputeQpResiduals(p, warm).Within(1e-9));
}

TEST_CASE("ClpSettings::Validate names the bad field", "[clp]") {
  ClpSettings s;
  s.primal_tolerance = 0.0;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("primal_tolerance"));
  s = ClpSettings{};
  s.max_iterations = 0;
  CHECK_THROWS_WITH(ClpSolver(s), Catch::Contains("max_iterations"));
}
