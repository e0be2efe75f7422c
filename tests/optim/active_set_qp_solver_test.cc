// ActiveSetQpSolver: known optima, KKT conditions of its answers, agreement with Ipopt, warm
// starts, singular Hessians, dependent equalities, and the failure statuses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/body_qp_example.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/make_solver.h"
#include "kkt_check.h"

using namespace stairplan::optim;
using stairplan::testing::CheckKkt;

namespace {

// A random strictly convex QP with box bounds, two-sided rows and equalities; feasible by
// construction (the rows' bounds bracket A x_feasible).
Program RandomQp(int n, int m, int equalities, unsigned seed, bool singular = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Program p;
  const VariableBlock x = p.AddVariables("x", n);
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i) for (int j = 0; j < n; ++j) M(i, j) = normal(rng);
  Eigen::MatrixXd Q = M * M.transpose() / n;
  if (singular) {
    Eigen::MatrixXd B = M.leftCols(n / 3);
    Q = B * B.transpose() / n;  // rank n/3
  } else {
    Q += 0.1 * Eigen::MatrixXd::Identity(n, n);
  }
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) g[i] = 3.0 * normal(rng);
  p.AddQuadraticCost(x, Q, g);
  Eigen::VectorXd x_feasible(n);
  for (int i = 0; i < n; ++i) x_feasible[i] = 0.5 * normal(rng);
  Eigen::MatrixXd A(m, n);
  for (int i = 0; i < m; ++i) for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  const Eigen::VectorXd ax = A * x_feasible;
  Eigen::VectorXd lo(m), hi(m);
  for (int i = 0; i < m; ++i) {
    if (i < equalities) {
      lo[i] = hi[i] = ax[i];
    } else {
      lo[i] = uniform(rng) < 0.3 ? -kInf : ax[i] - uniform(rng);
      hi[i] = uniform(rng) < 0.3 ? kInf : ax[i] + uniform(rng);
    }
  }
  p.AddLinearConstraint({{x, A}}, lo, hi, "rows");
  Eigen::VectorXd bl(n), bu(n);
  for (int i = 0; i < n; ++i) {
    bl[i] = x_feasible[i] - 0.2 - uniform(rng);
    bu[i] = x_feasible[i] + 0.2 + uniform(rng);
  }
  p.SetVariableBounds(x, bl, bu);
  return p;
}

}  // namespace

TEST_CASE("a small QP with an active inequality reaches its known optimum", "[active_set]") {
  // min (x-1)^2 + (y-2.5)^2 s.t. x - 2y >= -2, -x - 2y >= -6, -x + 2y >= -2, x, y >= 0
  // (the textbook example; optimum (1.4, 1.7), objective 0.8 for this scaling).
  Program p;
  const VariableBlock v = p.AddVariables("xy", 2);
  p.AddQuadraticCost(v, 2.0 * Eigen::Matrix2d::Identity(), Eigen::Vector2d(-2, -5));
  p.AddConstant(1.0 + 6.25);
  Eigen::MatrixXd A(3, 2);
  A << 1, -2, -1, -2, -1, 2;
  p.AddLinearConstraint({{v, A}}, Eigen::Vector3d(-2, -6, -2), Eigen::Vector3d::Constant(kInf), "rows");
  p.SetVariableBounds(v, Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(kInf));
  ActiveSetQpSolver solver;
  const SolveResult r = solver.Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.x[0] == Approx(1.4).margin(1e-12));
  CHECK(r.x[1] == Approx(1.7).margin(1e-12));
  CHECK(r.objective == Approx(0.8).margin(1e-12));
  CHECK(r.active_set.rows[0] == -1);  // x - 2y >= -2 holds with equality at its lower side
  CheckKkt(p, r, 1e-9);
}

TEST_CASE("random strictly convex QPs match Ipopt and satisfy KKT", "[active_set]") {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Program p = RandomQp(25, 30, 3, seed);
    ActiveSetQpSolver ours;
    IpoptSolver ipopt;
    const SolveResult a = ours.Solve(p);
    const SolveResult b = ipopt.Solve(p);
    INFO("seed " << seed);
    REQUIRE(a.status == SolveStatus::kSolved);
    REQUIRE(b.status == SolveStatus::kSolved);
    CHECK(a.objective == Approx(b.objective).epsilon(1e-6));
    CHECK((a.x - b.x).lpNorm<Eigen::Infinity>() < 1e-5);
    CheckKkt(p, a, 1e-8);
  }
}

TEST_CASE("block-diagonal banded Hessians (J0 solved per block) match Ipopt and satisfy KKT", "[active_set]") {
  // H in diagonal blocks of random sizes, each banded (second differences plus a diagonal, as
  // the body QP's), some variables with no Hessian at all (singular: proximal iterations); the
  // rows couple variables across blocks, so the active constraints mix the blocks' columns of J.
  for (unsigned seed = 1; seed <= 8; ++seed) {
    INFO("seed " << seed);
    const bool singular = seed % 2 == 0;
    Program p = RandomQp(40, 45, 2, seed);
    std::mt19937 rng(seed + 100);
    std::uniform_int_distribution<int> size(1, 12);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(40, 40);
    for (int start = 0; start < 40;) {
      const int b = std::min(size(rng), 40 - start);
      for (int i = start; i < start + b; ++i) {
        H(i, i) += 0.5 + 0.1 * (i % 3);
        if (i + 2 < start + b) {  // (x_i - 2 x_{i+1} + x_{i+2})^2
          const int k[3] = {i, i + 1, i + 2};
          const double w[3] = {1.0, -2.0, 1.0};
          for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) H(k[r], k[c]) += w[r] * w[c];
          }
        }
      }
      start += b;
    }
    if (singular) {
      for (int i = 3; i < 40; i += 7) {
        H.row(i).setZero();
        H.col(i).setZero();
      }
    }
    p.MutableHessian() = H;
    ActiveSetQpSolver ours;
    IpoptSolver ipopt;
    const SolveResult a = ours.Solve(p);
    const SolveResult b = ipopt.Solve(p);
    REQUIRE(a.status == SolveStatus::kSolved);
    REQUIRE(b.status == SolveStatus::kSolved);
    CHECK(a.objective == Approx(b.objective).epsilon(1e-6));
    CheckKkt(p, a, singular ? 1e-6 : 1e-8);
  }
}

TEST_CASE("singular Hessians (proximal iterations) match Ipopt", "[active_set]") {
  for (unsigned seed = 10; seed <= 13; ++seed) {
    const Program p = RandomQp(24, 20, 2, seed, /*singular=*/true);
    ActiveSetQpSolver ours;
    IpoptSolver ipopt;
    const SolveResult a = ours.Solve(p);
    const SolveResult b = ipopt.Solve(p);
    INFO("seed " << seed);
    REQUIRE(a.status == SolveStatus::kSolved);
    REQUIRE(b.status == SolveStatus::kSolved);
    CHECK(a.info.outer_iterations >= 1);
    CHECK(a.objective == Approx(b.objective).epsilon(1e-6).margin(1e-7));
    CHECK(p.MaxViolation(a.x) < 1e-8);
  }
}

TEST_CASE("a linear program (H = 0) solves to its vertex", "[active_set]") {
  // max x + y s.t. x + 2y <= 4, 3x + y <= 6, x, y >= 0: optimum (1.6, 1.2), value -2.8.
  Program p;
  const VariableBlock v = p.AddVariables("xy", 2);
  p.AddLinearCost(v, Eigen::Vector2d(-1, -1));
  Eigen::MatrixXd A(2, 2);
  A << 1, 2, 3, 1;
  p.AddLinearConstraint({{v, A}}, Eigen::Vector2d::Constant(-kInf), Eigen::Vector2d(4, 6), "rows");
  p.SetVariableBounds(v, Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(kInf));
  const SolveResult r = ActiveSetQpSolver().Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.x[0] == Approx(1.6).margin(1e-9));
  CHECK(r.x[1] == Approx(1.2).margin(1e-9));
  CHECK(r.objective == Approx(-2.8).margin(1e-9));
}

TEST_CASE("an unbounded linear program is reported as unbounded", "[active_set]") {
  // min -x - y s.t. x - y <= 1, x, y >= 0: the ray (1, 1) is feasible and descends forever.
  Program p;
  const VariableBlock v = p.AddVariables("xy", 2);
  p.AddLinearCost(v, Eigen::Vector2d(-1, -1));
  p.AddLinearConstraint({{v, Eigen::RowVector2d(1, -1)}}, Eigen::VectorXd::Constant(1, -kInf), Eigen::VectorXd::Ones(1), "row");
  p.SetVariableBounds(v, Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(kInf));
  CHECK(ActiveSetQpSolver().Solve(p).status == SolveStatus::kUnbounded);
  // Closing the ray with y <= 3 makes it bounded: optimum (4, 3).
  p.SetVariableBounds(v, Eigen::Vector2d::Zero(), Eigen::Vector2d(kInf, 3));
  const SolveResult r = ActiveSetQpSolver().Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.x[0] == Approx(4.0).margin(1e-9));
  CHECK(r.x[1] == Approx(3.0).margin(1e-9));
}

TEST_CASE("one solver handles programs of different sizes in turn", "[active_set]") {
  ActiveSetQpSolver solver;
  for (int n : {3, 5, 3}) {
    Program p;
    const VariableBlock v = p.AddVariables("v", n);
    p.AddQuadraticCost(v, Eigen::MatrixXd::Identity(n, n), -Eigen::VectorXd::Ones(n));
    p.SetVariableBounds(v, Eigen::VectorXd::Constant(n, -kInf), Eigen::VectorXd::Constant(n, 0.5));
    const SolveResult r = solver.Solve(p);
    REQUIRE(r.status == SolveStatus::kSolved);
    CHECK((r.x - Eigen::VectorXd::Constant(n, 0.5)).lpNorm<Eigen::Infinity>() < 1e-12);
    CHECK(r.bound_duals[0] == Approx(0.5));  // x + dual = 1 at the upper bound
  }
}

TEST_CASE("dependent equality rows are tolerated, contradictory ones are infeasible", "[active_set]") {
  Program p;
  const VariableBlock v = p.AddVariables("v", 3);
  p.AddQuadraticCost(v, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  Eigen::MatrixXd A(3, 3);
  A << 1, 1, 0, 0, 1, 1, 1, 2, 1;  // row 3 = row 1 + row 2
  const ConstraintRows rows = p.AddLinearConstraint({{v, A}}, Eigen::Vector3d(1, 1, 2), Eigen::Vector3d(1, 1, 2), "eq");
  ActiveSetQpSolver solver;
  SolveResult r = solver.Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  // min |v|^2 s.t. v1 + v2 = 1, v2 + v3 = 1: v = (1/3, 2/3, 1/3).
  CHECK(r.x[0] == Approx(1.0 / 3));
  CHECK(r.x[1] == Approx(2.0 / 3));
  CHECK(r.x[2] == Approx(1.0 / 3));
  p.SetConstraintBounds(rows, Eigen::Vector3d(1, 1, 2.5), Eigen::Vector3d(1, 1, 2.5));
  r = solver.Solve(p);
  CHECK(r.status == SolveStatus::kInfeasible);
}

TEST_CASE("an infeasible QP is reported as infeasible", "[active_set]") {
  Program p;
  const VariableBlock v = p.AddVariables("v", 2);
  p.AddQuadraticCost(v, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  Eigen::MatrixXd A(2, 2);
  A << 1, 1, 1, 1;
  p.AddLinearConstraint({{v, A}}, Eigen::Vector2d(2, -kInf), Eigen::Vector2d(kInf, 1), "contradiction");
  const SolveResult r = ActiveSetQpSolver().Solve(p);
  CHECK(r.status == SolveStatus::kInfeasible);
}

TEST_CASE("NaN in the data gives InvalidInput, a nonlinear program too", "[active_set]") {
  Program p;
  const VariableBlock v = p.AddVariables("v", 2);
  p.AddQuadraticCost(v, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  ActiveSetQpSolver solver;
  CHECK(solver.Solve(p).status == SolveStatus::kSolved);
  p.MutableHessian()(0, 1) = std::nan("");
  CHECK(solver.Solve(p).status == SolveStatus::kInvalidInput);
  p.MutableHessian()(0, 1) = 0.0;
  p.MutableLinearCost()[1] = std::nan("");
  CHECK(solver.Solve(p).status == SolveStatus::kInvalidInput);
  p.MutableLinearCost()[1] = 0.0;
  NonlinearCost cost{"quartic", {v}, [](const Eigen::VectorXd& x) { return x.array().pow(4).sum(); },
                     [](const Eigen::VectorXd& x, int, Eigen::Ref<Eigen::VectorXd> out) { out = 4 * x.array().pow(3).matrix(); }};
  p.AddNonlinearCost(cost);
  CHECK(solver.Solve(p).status == SolveStatus::kInvalidInput);
}

TEST_CASE("a 1 us time limit stops promptly with TimeLimit", "[active_set]") {
  const Program p = RandomQp(60, 80, 5, 42);
  ActiveSetQpSettings settings;
  settings.time_limit_s = 1e-6;
  ActiveSetQpSolver solver(settings);
  const SolveResult r = solver.Solve(p);
  CHECK(r.status == SolveStatus::kTimeLimit);
  settings.time_limit_s = kInf;
  settings.max_iterations = 2;
  ActiveSetQpSolver limited(settings);
  CHECK(limited.Solve(p).status == SolveStatus::kIterationLimit);
}

TEST_CASE("settings are validated naming the field", "[active_set]") {
  ActiveSetQpSettings s;
  s.feasibility_tol = -1;
  CHECK_THROWS_WITH(ActiveSetQpSolver(s), Catch::Contains("feasibility_tol"));
}

TEST_CASE("warm starts reproduce the cold solution with fewer iterations", "[active_set]") {
  BodyQpExample e = MakeBodyQpExample(40);
  ActiveSetQpSettings cold_settings;
  cold_settings.warm_start = false;
  ActiveSetQpSolver warm, cold(cold_settings);
  SolveResult rw, rc;
  int warm_iterations = 0, cold_iterations = 0;
  for (int cycle = 0; cycle < 50; ++cycle) {
    UpdateBodyQpExample(cycle, &e);
    warm.Solve(e.program, &rw);
    cold.Solve(e.program, &rc);
    REQUIRE(rw.status == SolveStatus::kSolved);
    REQUIRE(rc.status == SolveStatus::kSolved);
    CHECK((rw.x - rc.x).lpNorm<Eigen::Infinity>() < 1e-9);
    if (cycle > 0) {
      warm_iterations += rw.info.iterations;
      cold_iterations += rc.info.iterations;
    }
  }
  CHECK(warm_iterations < cold_iterations);
  // A stored active set works as a warm start for a fresh solver too.
  ActiveSetQpSolver fresh;
  fresh.SetWarmStart(rw.active_set);
  const SolveResult again = fresh.Solve(e.program);
  REQUIRE(again.status == SolveStatus::kSolved);
  CHECK(again.info.iterations == 0);
  CHECK((again.x - rw.x).lpNorm<Eigen::Infinity>() < 1e-9);
}

TEST_CASE("an active set given to a solver that keeps its factorisation is reached by drops and adds",
          "[active_set]") {
  // The solver last solved cycle 0; the set given is cycle 30's optimum. Reaching it from the kept
  // factorisation (not rebuilding it) must land on the same optimum, with nothing left to change.
  for (const unsigned seed : {3u, 4u, 5u}) {
    BodyQpExample e = MakeBodyQpExample(40);
    ActiveSetQpSolver hot, reference;
    SolveResult first, target, again;
    UpdateBodyQpExample(0, &e);
    hot.Solve(e.program, &first);
    REQUIRE(first.status == SolveStatus::kSolved);
    UpdateBodyQpExample(30, &e);
    reference.Solve(e.program, &target);
    REQUIRE(target.status == SolveStatus::kSolved);
    hot.SetWarmStart(target.active_set);
    hot.Solve(e.program, &again);
    REQUIRE(again.status == SolveStatus::kSolved);
    CHECK(again.info.iterations == 0);
    CHECK((again.x - target.x).lpNorm<Eigen::Infinity>() < 1e-9);
    // And on random QPs with rows and bounds: a foreign active set (another program's data of the
    // same shape) as the start still ends at the program's own optimum.
    Program a = RandomQp(30, 40, 3, seed), b = RandomQp(30, 40, 3, seed + 100);
    ActiveSetQpSolver solver;
    SolveResult ra, rb, rab;
    solver.Solve(a, &ra);
    REQUIRE(ra.status == SolveStatus::kSolved);
    ActiveSetQpSolver other;
    other.Solve(b, &rb);
    REQUIRE(rb.status == SolveStatus::kSolved);
    solver.SetWarmStart(rb.active_set);
    solver.Solve(a, &rab);
    REQUIRE(rab.status == SolveStatus::kSolved);
    CHECK((rab.x - ra.x).lpNorm<Eigen::Infinity>() < 1e-8);
    CheckKkt(a, rab, 1e-7);
  }
}

TEST_CASE("changed constraint rows re-solve from the previous active set", "[active_set]") {
  // The rate rows get slightly different coefficients each cycle (as a planner that relinearises
  // would do): the factorisation is rebuilt from the last active set instead of from nothing.
  BodyQpExample e = MakeBodyQpExample(40);
  ActiveSetQpSettings cold_settings;
  cold_settings.warm_start = false;
  ActiveSetQpSolver warm, cold(cold_settings);
  SolveResult rw, rc;
  int warm_iterations = 0, cold_iterations = 0;
  Eigen::MatrixXd coefficients = e.program.constraint_matrix().block(e.rates.start, e.height.start, e.rates.size, e.height.size);
  for (int cycle = 0; cycle < 20; ++cycle) {
    UpdateBodyQpExample(cycle, &e);
    e.program.SetConstraintCoefficients(e.rates, e.height, (1.0 + 0.01 * cycle) * coefficients);
    warm.Solve(e.program, &rw);
    cold.Solve(e.program, &rc);
    REQUIRE(rw.status == SolveStatus::kSolved);
    REQUIRE(rc.status == SolveStatus::kSolved);
    CHECK((rw.x - rc.x).lpNorm<Eigen::Infinity>() < 1e-9);
    if (cycle > 0) {
      warm_iterations += rw.info.iterations;
      cold_iterations += rc.info.iterations;
    }
  }
  CHECK(warm_iterations < cold_iterations);
}

TEST_CASE("active rows whose coefficients barely change stay active: no active-set change", "[active_set]") {
  // A planner that re-linearises every cycle rewrites its active rows with nearly the same
  // coefficients. They leave the factorisation (it depends on them) and must come straight back:
  // the start is then the optimum again. Waiting for the iteration to find them violated costs an
  // add each, and the restart without them drops neighbours whose multipliers needed them.
  BodyQpExample e = MakeBodyQpExample(40);
  UpdateBodyQpExample(5, &e);
  ActiveSetQpSolver solver;
  SolveResult first, again;
  solver.Solve(e.program, &first);
  REQUIRE(first.status == SolveStatus::kSolved);
  int changed = 0;
  for (const ConstraintRows& rows : {e.hip_heights, e.rates}) {
    for (int r = 0; r < rows.size && changed < 3; ++r) {
      if (first.active_set.rows[static_cast<std::size_t>(rows.start + r)] == 0) continue;
      for (const VariableBlock& block : {e.height, e.pitch}) {
        for (int k = 0; k < e.knots; ++k) {
          const double c = e.program.constraint_matrix()(rows.start + r, block.start + k);
          if (c != 0.0) e.program.SetConstraintCoefficient(rows, r, block, k, c * (1.0 + 1e-9));
        }
      }
      ++changed;
    }
  }
  REQUIRE(changed == 3);
  solver.Solve(e.program, &again);
  REQUIRE(again.status == SolveStatus::kSolved);
  CHECK(again.info.iterations == 0);
  CHECK(again.active_set.rows == first.active_set.rows);
  CHECK((again.x - first.x).lpNorm<Eigen::Infinity>() < 1e-6);
}

TEST_CASE("the automatic choice sends QPs to the active-set solver and NLPs to Ipopt", "[active_set]") {
  Program p;
  const VariableBlock v = p.AddVariables("v", 1);
  p.AddQuadraticCost(v, Eigen::MatrixXd::Identity(1, 1), Eigen::VectorXd::Zero(1));
  CHECK(MakeSolver(p)->name() == "active-set");
  p.AddNonlinearCost({"c", {v}, [](const Eigen::VectorXd& x) { return std::cosh(x[0]); },
                      [](const Eigen::VectorXd& x, int, Eigen::Ref<Eigen::VectorXd> out) { out[0] = std::sinh(x[0]); }});
  CHECK(MakeSolver(p)->name() == "ipopt");
  CHECK_THROWS_WITH(MakeSolver("gurobi"), Catch::Contains("gurobi"));
}
