// The benchmark measures: qpbenchmark's residuals on known KKT points, the shifted geometric
// mean, the regimes' loops (a warm sequence warm-starts Ipopt with multipliers, a cold one does
// not), and the summary's success counts.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/body_qp_example.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/qp_benchmark.h"

using namespace stairplan::optim;

namespace {

// min 0.5 |x|^2 - x1 - x2 s.t. x1 + x2 <= 1, x1 >= 0.8: x = (0.8, 0.2), the row's dual and x1's bound dual known.
Program BenchTinyQp() {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  p.AddQuadraticCost(x, Eigen::Matrix2d::Identity(), Eigen::Vector2d(-1.0, -1.0));
  p.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 1.0)}}, Eigen::VectorXd::Constant(1, -kInf),
                        Eigen::VectorXd::Constant(1, 1.0), "sum");
  p.SetVariableBounds(x, Eigen::Vector2d(0.8, -kInf), Eigen::Vector2d::Constant(kInf));
  return p;
}

SolveResult BenchTinySolution() {
  // Stationarity: x - 1 + y + z = 0 -> y = 0.8 (upper side, >= 0), z1 = 1 - 0.8 - 0.8 = -0.6 (lower side).
  SolveResult r;
  r.status = SolveStatus::kSolved;
  r.x = Eigen::Vector2d(0.8, 0.2);
  r.row_duals = Eigen::VectorXd::Constant(1, 0.8);
  r.bound_duals = Eigen::Vector2d(-0.6, 0.0);
  return r;
}

}  // namespace

TEST_CASE("qpbenchmark residuals vanish at a KKT point and measure each defect", "[qp_bench]") {
  const Program p = BenchTinyQp();
  SolveResult r = BenchTinySolution();
  QpResiduals at = ComputeQpResiduals(p, r);
  CHECK(at.primal == Approx(0.0).margin(1e-15));
  CHECK(at.dual == Approx(0.0).margin(1e-15));
  CHECK(at.gap == Approx(0.0).margin(1e-15));
  CHECK(at.Within(1e-9));
  r.x[1] = 0.3;  // breaks the row by 0.1; stationarity by 0.1; gap x'x + g'x + 0.8 - 0.48 moves too
  at = ComputeQpResiduals(p, r);
  CHECK(at.primal == Approx(0.1));
  CHECK(at.dual == Approx(0.1));
  CHECK(at.gap == Approx(std::abs(0.64 + 0.09 - 1.1 + 0.8 - 0.48)));
  r = BenchTinySolution();
  r.row_duals[0] = 0.9;  // stationarity off by 0.1, gap by 0.1 (upper 1 x 0.1)
  at = ComputeQpResiduals(p, r);
  CHECK(at.primal == Approx(0.0).margin(1e-15));
  CHECK(at.dual == Approx(0.1));
  CHECK(at.gap == Approx(0.1));
  CHECK_FALSE(at.Within(1e-6));
}

TEST_CASE("The shifted geometric mean and the summary count as qpbenchmark does", "[qp_bench]") {
  CHECK(ShiftedGeometricMean({0.0, 90.0}, 10.0) == Approx(std::sqrt(10.0 * 100.0) - 10.0));
  CHECK(ShiftedGeometricMean({5.0, 5.0, 5.0}, 10.0) == Approx(5.0));
  QpSample good, rough, failed;
  good.status = rough.status = SolveStatus::kSolved;
  good.residuals = {1e-12, 1e-12, 1e-12};
  rough.residuals = {1e-8, 1e-12, 1e-12};
  failed.status = SolveStatus::kNumericalError;
  failed.residuals = {0, 0, 0};
  good.cpu_us = rough.cpu_us = failed.cpu_us = 90.0;
  const QpBenchSummary s = Summarise({good, rough, failed}, 1e6);
  CHECK(s.problems == 3);
  CHECK(s.solved_mid == 2);
  CHECK(s.solved_high == 1);
  CHECK(s.shifted_geomean_us == Approx(std::cbrt(100.0 * 100.0 * (1e6 + 10.0)) - 10.0));
}

TEST_CASE("Regimes: a warm sequence warm-starts every solver, Ipopt with multipliers", "[qp_bench]") {
  BodyQpExample e = MakeBodyQpExample(10);
  const auto apply = [&e](int k, Program* p) {
    UpdateBodyQpExample(k, &e);
    *p = e.program;
  };
  Program program = e.program;
  const SolverFactory ours = [] { return std::make_unique<ActiveSetQpSolver>(); };
  const std::vector<QpSample> warm = MeasureSequence(ours, SolveRegime::kWarmSequence, &program, 6, apply);
  const std::vector<QpSample> cold = MeasureSequence(ours, SolveRegime::kCold, &program, 6, apply);
  REQUIRE(warm.size() == 5);  // QP 0 is the cold start, not counted
  REQUIRE(cold.size() == 6);
  for (std::size_t k = 0; k < warm.size(); ++k) {
    CHECK(warm[k].SolvedWithin(kMidAccuracy));
    CHECK(warm[k].objective == Approx(cold[k + 1].objective).epsilon(1e-9));
  }
  CHECK_THROWS(MeasureSequence(ours, SolveRegime::kIdenticalResolve, &program, 2, apply));
  // Ipopt: WarmStartFrom hands over x and the multipliers.
  IpoptSolver ipopt;
  const SolveResult first = ipopt.Solve(program);
  REQUIRE(first.solved());
  WarmStartFrom(first, &ipopt, &program);
  CHECK(ipopt.has_dual_guess());
  CHECK(program.initial_guess() == first.x);
  const SolveResult again = ipopt.Solve(program);
  CHECK(again.solved());
  CHECK(again.info.iterations < first.info.iterations);
  // Cold and identical re-solve on one problem.
  const QpSample c = MeasureCold(ours, program, {3, 0.0});
  const QpSample i = MeasureIdenticalResolve(ours, program, {3, 0.0});
  CHECK(c.SolvedWithin(kMidAccuracy));
  CHECK(i.SolvedWithin(kMidAccuracy));
  CHECK(i.iterations == 0);  // the same active set again
}
