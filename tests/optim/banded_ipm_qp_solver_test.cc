// BandedIpmQpSolver: KKT conditions and the active-set solver's optimum on the body QP example,
// on random knot-structured QPs (variables in blocks by quantity, so the band has to be found),
// on the body planner's own QP, on small Maros-Meszaros problems; the failure statuses; the
// band it finds; its settings' checks.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <random>
#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/crawl_planner.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/banded_ipm_qp_solver.h"
#include "stairplan/optim/body_qp_example.h"
#include "stairplan/optim/qp_residuals.h"
#include "stairplan/optim/qps_reader.h"
#include "stairplan/solvers/make_solver.h"
#include "kkt_check.h"
#include "maros_meszaros_index.h"
#include "test_paths.h"

using namespace stairplan::optim;
using stairplan::testing::CheckKkt;
using stairplan::testing::ReadMarosMeszarosIndex;
using stairplan::testing::SharedPath;

namespace {

// Both solvers on `p`: ours solved, KKT at 1e-8, qpbenchmark's residuals at 1e-8, and the active
// set solver's objective (relative 1e-8).
void CheckAgainstActiveSet(const Program& p) {
  BandedIpmQpSolver ipm;
  const SolveResult r = ipm.Solve(p);
  INFO("status " << ToString(r.status) << " after " << r.info.iterations << " iterations");
  REQUIRE(r.status == SolveStatus::kSolved);
  CheckKkt(p, r, 1e-8);
  const QpResiduals residuals = ComputeQpResiduals(p, r);
  CHECK(residuals.Within(1e-8));
  ActiveSetQpSolver reference;
  const SolveResult a = reference.Solve(p);
  REQUIRE(a.status == SolveStatus::kSolved);
  CHECK(std::abs(r.objective - a.objective) <= 1e-8 * (1.0 + std::abs(a.objective)));
}

struct KnotQpOptions {
  int knots = 30;
  bool bounds = true;        // box bounds on every variable (some binding)
  bool inactive_rows = false;  // add rows with bounds far away
  bool equalities = false;   // pin knot 0
  unsigned seed = 1;
};

// A random QP with knot structure: 4 quantities per knot in blocks by quantity (x = [q0 of every
// knot, q1 of every knot, ...]); costs on values, first and second differences; rows coupling a
// knot's quantities with the next knot's. Feasible by construction (rows bracket A x_feasible).
Program KnotQp(const KnotQpOptions& o) {
  constexpr int kQuantities = 4;
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int n = kQuantities * o.knots;
  const auto var = [&](int q, int k) { return q * o.knots + k; };
  Program p;
  const VariableBlock x = p.AddVariables("x", n);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  for (int q = 0; q < kQuantities; ++q) {
    const double w0 = 0.1 + uniform(rng), w1 = 1.0 + 5 * uniform(rng), w2 = 10.0 * uniform(rng);
    for (int k = 0; k < o.knots; ++k) h(var(q, k), var(q, k)) += w0;
    for (int k = 0; k + 1 < o.knots; ++k) {  // w1 (x_{k+1} - x_k)^2
      const int a = var(q, k), b = var(q, k + 1);
      h(a, a) += w1, h(b, b) += w1, h(a, b) -= w1, h(b, a) -= w1;
    }
    for (int k = 0; k + 2 < o.knots; ++k) {  // w2 (x_{k+2} - 2 x_{k+1} + x_k)^2
      const int i[3] = {var(q, k), var(q, k + 1), var(q, k + 2)};
      const double c[3] = {1.0, -2.0, 1.0};
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) h(i[a], i[b]) += w2 * c[a] * c[b];
      }
    }
  }
  // A cross term between quantities 0 and 1 of each knot (height and pitch are coupled).
  for (int k = 0; k < o.knots; ++k) {
    h(var(0, k), var(1, k)) += 0.3;
    h(var(1, k), var(0, k)) += 0.3;
  }
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) g[i] = 3.0 * normal(rng);
  p.AddQuadraticCost(x, h, g);
  Eigen::VectorXd feasible(n);
  for (int i = 0; i < n; ++i) feasible[i] = 0.2 * normal(rng);
  const int per_knot = o.inactive_rows ? 3 : 2;
  const int m = per_knot * (o.knots - 1);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, n);
  Eigen::VectorXd lo(m), hi(m);
  for (int k = 0; k + 1 < o.knots; ++k) {
    for (int r = 0; r < per_knot; ++r) {
      const int row = per_knot * k + r;
      for (int q = 0; q < kQuantities; ++q) {
        if (uniform(rng) < 0.6) a(row, var(q, k)) = normal(rng);
        if (uniform(rng) < 0.4) a(row, var(q, k + 1)) = normal(rng);
      }
      const double value = a.row(row).dot(feasible);
      const double width = r == 2 ? 1e3 : 0.05 + 0.1 * uniform(rng);
      lo[row] = value - width * uniform(rng);
      hi[row] = uniform(rng) < 0.2 ? kInf : value + width * uniform(rng);
    }
  }
  p.AddLinearConstraint({{x, a}}, lo, hi, "rows");
  Eigen::VectorXd vlo = Eigen::VectorXd::Constant(n, -kInf), vhi = Eigen::VectorXd::Constant(n, kInf);
  if (o.bounds) {
    for (int i = 0; i < n; ++i) {
      vlo[i] = feasible[i] - 0.3 * uniform(rng);
      vhi[i] = feasible[i] + 0.3 * uniform(rng);
    }
  }
  if (o.equalities) {
    for (int q = 0; q < kQuantities; ++q) vlo[var(q, 0)] = vhi[var(q, 0)] = feasible[var(q, 0)];
  }
  p.SetVariableBounds(x, vlo, vhi);
  return p;
}

// The body planner on the default staircase, forward, with the builtin robot's crawl: the
// planner whose per-cycle QPs the flight tests solve, beside the stairs, map and footsteps it
// was built from. One per test.
struct BodyPlannerFlight {
  const stairplan::Staircase stairs{stairplan::StairSpec{}};
  const stairplan::ConstrainedMap map = stairplan::ConstrainedMap::FromStaircase(stairs, stairplan::Facing::kForward);
  const stairplan::Plan footsteps = stairplan::PlanCrawl(stairplan::BuiltinRobot(), stairs, map);
  stairplan::BodyPlanner planner{stairplan::BuiltinRobot(), stairs, map, footsteps, stairplan::BodyPlannerSettings{}};
};
// The planner's cycle [s] in the flight tests.
constexpr double kPeriod = 0.003;

}  // namespace

TEST_CASE("BandedIpmQpSolver: the body QP example's optimum and KKT conditions", "[banded-ipm]") {
  BodyQpExample e = MakeBodyQpExample(40);
  for (int cycle = 0; cycle < 5; ++cycle) {
    INFO("cycle " << cycle);
    UpdateBodyQpExample(cycle * 7, &e);
    CheckAgainstActiveSet(e.program);
  }
}

TEST_CASE("BandedIpmQpSolver: random knot-structured QPs, blocks by quantity reordered to a band", "[banded-ipm]") {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    for (const bool bounds : {true, false}) {
      for (const bool inactive : {false, true}) {
        KnotQpOptions o;
        o.seed = seed;
        o.bounds = bounds;
        o.inactive_rows = inactive;
        o.equalities = seed % 2 == 0;
        o.knots = 20 + 5 * static_cast<int>(seed);
        INFO("seed " << seed << " bounds " << bounds << " inactive rows " << inactive);
        const Program p = KnotQp(o);
        CheckAgainstActiveSet(p);
        BandedIpmQpSolver ipm;
        ipm.Solve(p);
        // Knot k's 4 quantities couple with knot k + 2's (second differences): in knot order
        // the band is under 3 knots wide (11); reverse Cuthill-McKee finds one of 16-17. In the
        // program's order (blocks by quantity) it is over 2 blocks: at least 2 * knots.
        CHECK(ipm.reordered());
        CHECK(ipm.bandwidth() <= 20);
      }
    }
  }
}

TEST_CASE("BandedIpmQpSolver: a dense row falls back to the full band and stays correct", "[banded-ipm]") {
  KnotQpOptions o;
  o.knots = 15;
  Program p = KnotQp(o);
  const int n = p.num_variables();
  Program dense;
  const VariableBlock x = dense.AddVariables("x", n);
  dense.AddQuadraticCost(x, p.hessian(), p.linear_cost());
  Eigen::MatrixXd a(p.num_rows() + 1, n);
  a.topRows(p.num_rows()) = p.constraint_matrix();
  a.bottomRows(1).setOnes();  // a sum row couples every variable
  Eigen::VectorXd lo(p.num_rows() + 1), hi(p.num_rows() + 1);
  lo << p.row_lower(), -kInf;
  hi << p.row_upper(), 1.0;
  dense.AddLinearConstraint({{x, a}}, lo, hi);
  dense.SetVariableBounds(x, p.variable_lower(), p.variable_upper());
  CheckAgainstActiveSet(dense);
  BandedIpmQpSolver ipm;
  ipm.Solve(dense);
  CHECK(ipm.bandwidth() == n - 1);
}

TEST_CASE("BandedIpmQpSolver: the body planner's own QP along a flight", "[banded-ipm]") {
  BodyPlannerFlight flight;
  stairplan::BodyPlanner& planner = flight.planner;
  stairplan::BodyState state = planner.StartState();
  int checked = 0;
  for (int cycle = 0; cycle * kPeriod < 4.0; ++cycle) {
    const double now = cycle * kPeriod;
    planner.Update(state, stairplan::BodyCommand{}, now);
    state = planner.Interpolate(now + kPeriod);
    if (cycle % 150 != 0) continue;
    INFO("t = " << now);
    CheckAgainstActiveSet(planner.qp().program());
    ++checked;
  }
  CHECK(checked >= 8);
}

TEST_CASE("BandedIpmQpSolver: small Maros-Meszaros problems reach the published optima", "[banded-ipm][conformance]") {
  const std::string dir = SharedPath("data/qp/maros_meszaros");
  if (dir.empty()) {
    WARN("Maros-Meszaros problems for banded-ipm skipped: ../shared not found");
    return;
  }
  std::map<std::string, double> optimum;
  for (const auto& e : ReadMarosMeszarosIndex(dir)) optimum[e.name] = e.optimum;
  REQUIRE(optimum.size() == 34);
  for (const char* problem : {"HS21", "HS35", "HS76", "HS118", "GENHS28", "QAFIRO", "DUALC1", "CVXQP1_S"}) {
    INFO(problem);
    const QpsProblem q = ReadQpsFile(dir + "/" + problem + ".SIF");
    BandedIpmQpSolver ipm;
    const SolveResult r = ipm.Solve(q.program);
    REQUIRE(r.status == SolveStatus::kSolved);
    const double expected = optimum.at(problem);
    CHECK(std::abs(r.objective - expected) <= 1e-6 * std::abs(expected));
    CHECK(ComputeQpResiduals(q.program, r).Within(1e-8 * (1.0 + std::abs(expected))));
  }
}

TEST_CASE("BandedIpmQpSolver: infeasible, unbounded and limited solves say so", "[banded-ipm]") {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  p.AddQuadraticCost(x, Eigen::Matrix2d::Identity(), Eigen::Vector2d(1.0, -1.0));
  SECTION("rows that contradict each other") {
    p.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 1.0)}}, Eigen::VectorXd::Constant(1, 2.0),
                          Eigen::VectorXd::Constant(1, kInf));
    p.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 1.0)}}, Eigen::VectorXd::Constant(1, -kInf),
                          Eigen::VectorXd::Constant(1, 1.0));
    p.SetVariableBounds(x, Eigen::Vector2d(-5.0, -5.0), Eigen::Vector2d(5.0, 5.0));
    BandedIpmQpSolver ipm;
    const SolveResult r = ipm.Solve(p);
    CHECK(r.status == SolveStatus::kInfeasible);
    CHECK(r.x.allFinite());
  }
  SECTION("a row's lower bound above its upper bound (the setters refuse it; a reader need not)") {
    p.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 0.0)}}, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
    p.MutableRowLower()[0] = 1.0;
    CHECK(BandedIpmQpSolver().Solve(p).status == SolveStatus::kInfeasible);
  }
  SECTION("a linear objective falling along a free direction") {
    Program lp;
    const VariableBlock y = lp.AddVariables("y", 2);
    lp.AddLinearCost(y, Eigen::Vector2d(-1.0, 0.0));
    lp.AddLinearConstraint({{y, Eigen::RowVector2d(1.0, -1.0)}}, Eigen::VectorXd::Constant(1, -1.0),
                           Eigen::VectorXd::Constant(1, 1.0));
    lp.SetVariableBounds(y, Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(kInf, kInf));
    const SolveResult r = BandedIpmQpSolver().Solve(lp);
    CHECK(r.status == SolveStatus::kUnbounded);
  }
  SECTION("a NaN anywhere in H or A (Solver's check sums in lanes of sixteen, then a tail)") {
    BodyQpExample e = MakeBodyQpExample(40);
    Program& q = e.program;
    for (const Eigen::Index i : {Eigen::Index{0}, q.hessian().size() / 2, q.hessian().size() - 1}) {
      const double kept = q.hessian().data()[i];
      q.MutableHessian().data()[i] = std::nan("");
      CHECK(BandedIpmQpSolver().Solve(q).status == SolveStatus::kInvalidInput);
      q.MutableHessian().data()[i] = kept;
    }
    for (const Eigen::Index i : {Eigen::Index{3}, q.constraint_matrix().size() - 1}) {
      const double kept = q.constraint_matrix().data()[i];
      q.MutableConstraintMatrix().data()[i] = std::nan("");
      CHECK(BandedIpmQpSolver().Solve(q).status == SolveStatus::kInvalidInput);
      q.MutableConstraintMatrix().data()[i] = kept;
    }
    CHECK(BandedIpmQpSolver().Solve(q).status == SolveStatus::kSolved);
    Program small;  // 5 x 5: one lane of sixteen and a tail of nine
    small.AddQuadraticCost(small.AddVariables("z", 5), Eigen::MatrixXd::Identity(5, 5), Eigen::VectorXd::Ones(5));
    for (const Eigen::Index i : {Eigen::Index{0}, Eigen::Index{15}, Eigen::Index{16}, Eigen::Index{24}}) {
      const double kept = small.hessian().data()[i];
      small.MutableHessian().data()[i] = std::nan("");
      CHECK(BandedIpmQpSolver().Solve(small).status == SolveStatus::kInvalidInput);
      small.MutableHessian().data()[i] = kept;
    }
  }
  SECTION("the iteration and time limits") {
    BodyQpExample e = MakeBodyQpExample(40);
    BandedIpmQpSettings settings;
    settings.max_iterations = 2;
    CHECK(BandedIpmQpSolver(settings).Solve(e.program).status == SolveStatus::kIterationLimit);
    settings.max_iterations = 100;
    settings.time_limit_s = 1e-9;
    CHECK(BandedIpmQpSolver(settings).Solve(e.program).status == SolveStatus::kTimeLimit);
  }
}

TEST_CASE("BandedIpmQpSolver: settings name the field they reject, MakeSolver knows it", "[banded-ipm]") {
  BandedIpmQpSettings settings;
  settings.step_fraction = 1.0;
  CHECK_THROWS_WITH(BandedIpmQpSolver(settings), Catch::Contains("step_fraction"));
  settings = {};
  settings.tolerance = 0.0;
  CHECK_THROWS_WITH(BandedIpmQpSolver(settings), Catch::Contains("tolerance"));
  settings = {};
  settings.max_iterations = 0;
  CHECK_THROWS_WITH(BandedIpmQpSolver(settings), Catch::Contains("max_iterations"));
  CHECK(MakeSolver("banded-ipm")->name() == "banded-ipm");
  CHECK_THROWS_WITH(MakeSolver("banded"), Catch::Contains("banded-ipm"));
  auto limited = MakeSolver("banded-ipm", 0.5);
  CHECK(dynamic_cast<BandedIpmQpSolver&>(*limited).settings().time_limit_s == 0.5);
}

TEST_CASE("BandedIpmQpSolver: warm along the body planner's cycles, the last active set first", "[banded-ipm]") {
  BodyPlannerFlight flight;
  stairplan::BodyPlanner& planner = flight.planner;
  stairplan::BodyState state = planner.StartState();
  BandedIpmQpSolver warm;
  BandedIpmQpSettings cold_settings;
  cold_settings.warm_start = false;
  BandedIpmQpSolver cold(cold_settings);
  int solves = 0, warm_hits = 0, cold_hits = 0;
  for (int cycle = 0; cycle * kPeriod < 3.0; ++cycle) {
    const double now = cycle * kPeriod;
    planner.Update(state, stairplan::BodyCommand{}, now);
    state = planner.Interpolate(now + kPeriod);
    if (cycle % 3 != 0) continue;
    const Program& p = planner.qp().program();
    INFO("t = " << now);
    const SolveResult r = warm.Solve(p);
    REQUIRE(r.status == SolveStatus::kSolved);
    CheckKkt(p, r, 1e-8);
    CHECK(ComputeQpResiduals(p, r).Within(1e-8));
    // A warm solve is the polish alone (no iterations); a cold one never is.
    CHECK((r.info.iterations == 0) == warm.warm_started());
    const SolveResult c = cold.Solve(p);
    REQUIRE(c.status == SolveStatus::kSolved);
    CHECK(!cold.warm_started());
    CHECK(c.info.iterations > 0);
    CHECK(std::abs(r.objective - c.objective) <= 1e-8 * (1.0 + std::abs(c.objective)));
    ++solves;
    warm_hits += warm.warm_started() ? 1 : 0;
    cold_hits += cold.warm_started() ? 1 : 0;
  }
  INFO(warm_hits << " of " << solves << " solves warm");
  CHECK(solves >= 300);
  CHECK(warm_hits >= solves / 2);  // the active set holds over most 9 ms steps of the flight
  CHECK(warm_hits < solves);       // and not over all of them: the fallback was exercised
  CHECK(cold_hits == 0);
}

TEST_CASE("BandedIpmQpSolver: a warm start whose active set no longer holds falls back to the interior point",
          "[banded-ipm]") {
  KnotQpOptions o;
  o.seed = 4;
  Program p = KnotQp(o);
  BandedIpmQpSolver ipm;
  const SolveResult first = ipm.Solve(p);
  REQUIRE(first.status == SolveStatus::kSolved);
  CHECK(!ipm.warm_started());
  // The same program again: the last active set solves it at once.
  const SolveResult again = ipm.Solve(p);
  REQUIRE(again.status == SolveStatus::kSolved);
  CHECK(ipm.warm_started());
  CHECK(again.info.iterations == 0);
  CHECK(std::abs(again.objective - first.objective) <= 1e-9 * (1.0 + std::abs(first.objective)));
  // The linear cost reversed: the optimum moves to other sides, so the last active set fails
  // the polish's checks.
  p.MutableLinearCost() = -p.linear_cost();
  const SolveResult moved = ipm.Solve(p);
  CHECK(!ipm.warm_started());
  REQUIRE(moved.status == SolveStatus::kSolved);
  CHECK(moved.info.iterations > 0);
  CheckKkt(p, moved, 1e-8);
  ActiveSetQpSolver reference;
  const SolveResult a = reference.Solve(p);
  REQUIRE(a.status == SolveStatus::kSolved);
  CHECK(std::abs(moved.objective - a.objective) <= 1e-8 * (1.0 + std::abs(a.objective)));
}
