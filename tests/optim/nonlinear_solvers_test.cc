// Ipopt and NLopt on nonlinear programs with known optima (Hock-Schittkowski 71 and 100), the
// derivative-free option, and time limits that hold on every solve.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"
#include "stairplan/solvers/make_solver.h"

using namespace stairplan::optim;

namespace {

// HS71: min x1 x4 (x1 + x2 + x3) + x3 s.t. x1 x2 x3 x4 >= 25, |x|^2 = 40, 1 <= x <= 5
// (`product` instead of 25 for a nearby problem).
Program Hs71(double product = 25) {
  Program p;
  const VariableBlock x = p.AddVariables("x", 4);
  p.SetVariableBounds(x, Eigen::Vector4d::Constant(1), Eigen::Vector4d::Constant(5));
  p.SetInitialGuess(x, Eigen::Vector4d(1, 5, 5, 1));
  p.AddNonlinearCost({"objective", {x},
                      [](const Eigen::VectorXd& v) { return v[0] * v[3] * (v[0] + v[1] + v[2]) + v[2]; },
                      [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::VectorXd> g) {
                        g[0] = v[3] * (2 * v[0] + v[1] + v[2]);
                        g[1] = v[0] * v[3];
                        g[2] = v[0] * v[3] + 1;
                        g[3] = v[0] * (v[0] + v[1] + v[2]);
                      }});
  NonlinearConstraint c;
  c.name = "product_and_sphere";
  c.blocks = {x};
  c.lower = Eigen::Vector2d(product, 40);
  c.upper = Eigen::Vector2d(kInf, 40);
  c.value = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::VectorXd> out) {
    out[0] = v.prod();
    out[1] = v.squaredNorm();
  };
  c.jacobian = [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::MatrixXd> J) {
    J.row(0) << v[1] * v[2] * v[3], v[0] * v[2] * v[3], v[0] * v[1] * v[3], v[0] * v[1] * v[2];
    J.row(1) = 2 * v.transpose();
  };
  p.AddNonlinearConstraint(c);
  return p;
}

// HS100: seven variables, a polynomial objective and four polynomial inequalities.
Program Hs100() {
  Program p;
  const VariableBlock x = p.AddVariables("x", 7);
  Eigen::VectorXd x0(7);
  x0 << 1, 2, 0, 4, 0, 1, 1;
  p.SetInitialGuess(x, x0);
  p.AddNonlinearCost({"objective", {x},
                      [](const Eigen::VectorXd& v) {
                        return std::pow(v[0] - 10, 2) + 5 * std::pow(v[1] - 12, 2) + std::pow(v[2], 4) +
                               3 * std::pow(v[3] - 11, 2) + 10 * std::pow(v[4], 6) + 7 * v[5] * v[5] +
                               std::pow(v[6], 4) - 4 * v[5] * v[6] - 10 * v[5] - 8 * v[6];
                      },
                      [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::VectorXd> g) {
                        g[0] = 2 * (v[0] - 10);
                        g[1] = 10 * (v[1] - 12);
                        g[2] = 4 * std::pow(v[2], 3);
                        g[3] = 6 * (v[3] - 11);
                        g[4] = 60 * std::pow(v[4], 5);
                        g[5] = 14 * v[5] - 4 * v[6] - 10;
                        g[6] = 4 * std::pow(v[6], 3) - 4 * v[5] - 8;
                      }});
  NonlinearConstraint c;
  c.name = "hs100";
  c.blocks = {x};
  c.lower = Eigen::Vector4d::Zero();
  c.upper = Eigen::Vector4d::Constant(kInf);
  c.value = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::VectorXd> out) {
    out[0] = 127 - 2 * v[0] * v[0] - 3 * std::pow(v[1], 4) - v[2] - 4 * v[3] * v[3] - 5 * v[4];
    out[1] = 282 - 7 * v[0] - 3 * v[1] - 10 * v[2] * v[2] - v[3] + v[4];
    out[2] = 196 - 23 * v[0] - v[1] * v[1] - 6 * v[5] * v[5] + 8 * v[6];
    out[3] = -4 * v[0] * v[0] - v[1] * v[1] + 3 * v[0] * v[1] - 2 * v[2] * v[2] - 5 * v[5] + 11 * v[6];
  };
  c.jacobian = [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::MatrixXd> J) {
    J.setZero();
    J.row(0) << -4 * v[0], -12 * std::pow(v[1], 3), -1, -8 * v[3], -5, 0, 0;
    J.row(1) << -7, -3, -20 * v[2], -1, 1, 0, 0;
    J.row(2) << -23, -2 * v[1], 0, 0, 0, -12 * v[5], 8;
    J.row(3) << -8 * v[0] + 3 * v[1], -2 * v[1] + 3 * v[0], -4 * v[2], 0, 0, -5, 11;
  };
  p.AddNonlinearConstraint(c);
  return p;
}

constexpr double kHs71 = 17.0140173;
constexpr double kHs100 = 680.6300573;

}  // namespace

TEST_CASE("Ipopt solves HS71 and HS100 to their published optima", "[nonlinear]") {
  IpoptSolver ipopt;
  const SolveResult a = ipopt.Solve(Hs71());
  REQUIRE(a.status == SolveStatus::kSolved);
  CHECK(a.objective == Approx(kHs71).epsilon(1e-6));
  CHECK(Hs71().MaxViolation(a.x) < 1e-7);
  const SolveResult b = ipopt.Solve(Hs100());
  REQUIRE(b.status == SolveStatus::kSolved);
  CHECK(b.objective == Approx(kHs100).epsilon(1e-6));
  CHECK(Hs100().MaxViolation(b.x) < 1e-7);
}

TEST_CASE("NLopt SLSQP solves HS71 and HS100 to their published optima", "[nonlinear]") {
  NloptSolver slsqp;
  const SolveResult a = slsqp.Solve(Hs71());
  REQUIRE(a.status == SolveStatus::kSolved);
  CHECK(a.objective == Approx(kHs71).epsilon(1e-6));
  const SolveResult b = slsqp.Solve(Hs100());
  REQUIRE(b.status == SolveStatus::kSolved);
  CHECK(b.objective == Approx(kHs100).epsilon(1e-6));
}

TEST_CASE("NLopt's derivative-free COBYLA solves a constrained problem", "[nonlinear]") {
  // min (x - 2)^2 + (y - 1)^2 s.t. x + y <= 2: optimum (1.5, 0.5), value 0.5.
  Program p;
  const VariableBlock v = p.AddVariables("v", 2);
  p.AddQuadraticCost(v, 2 * Eigen::Matrix2d::Identity(), Eigen::Vector2d(-4, -2));
  p.AddConstant(5);
  p.AddLinearConstraint({{v, Eigen::RowVector2d(1, 1)}}, Eigen::VectorXd::Constant(1, -kInf), Eigen::VectorXd::Constant(1, 2), "sum");
  p.SetVariableBounds(v, Eigen::Vector2d::Constant(-10), Eigen::Vector2d::Constant(10));
  NloptSettings s;
  s.algorithm = NloptSettings::Algorithm::kCobyla;
  s.xtol_rel = 1e-10;
  const SolveResult r = NloptSolver(s).Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.x[0] == Approx(1.5).margin(1e-5));
  CHECK(r.x[1] == Approx(0.5).margin(1e-5));
  CHECK(r.objective == Approx(0.5).margin(1e-5));
}

TEST_CASE("Ipopt's QP duals follow the documented convention", "[nonlinear]") {
  // min 0.5 |x|^2 s.t. x1 + x2 >= 2, x1 <= 0.5: x = (0.5, 1.5); row dual -1.5, bound dual +1.
  Program p;
  const VariableBlock v = p.AddVariables("v", 2);
  p.AddQuadraticCost(v, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero());
  p.AddLinearConstraint({{v, Eigen::RowVector2d(1, 1)}}, Eigen::VectorXd::Constant(1, 2), Eigen::VectorXd::Constant(1, kInf), "sum");
  p.SetVariableBounds(v, Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(0.5, kInf));
  const SolveResult r = IpoptSolver().Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.x[0] == Approx(0.5).margin(1e-7));
  CHECK(r.row_duals[0] == Approx(-1.5).margin(1e-6));
  CHECK(r.bound_duals[0] == Approx(1.0).margin(1e-6));
  CHECK(r.info.dual_residual < 1e-6);
}

TEST_CASE("Ipopt's nonlinear multipliers satisfy the KKT conditions with the documented signs", "[nonlinear]") {
  const Program p = Hs71();
  const SolveResult r = IpoptSolver().Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  REQUIRE(r.nonlinear_duals.size() == 2);
  // grad f + J' nonlinear_duals + bound_duals = 0 (no linear rows here).
  Eigen::VectorXd residual(4);
  p.nonlinear_costs()[0].gradient(r.x, 0, residual);
  Eigen::MatrixXd jac(2, 4);
  p.nonlinear_constraints()[0].jacobian(r.x, 0, jac);
  residual += jac.transpose() * r.nonlinear_duals + r.bound_duals;
  CHECK(residual.lpNorm<Eigen::Infinity>() < 1e-6);
  CHECK(r.nonlinear_duals[0] < -0.1);   // the product sits on its lower bound 25
  CHECK(r.bound_duals[0] < -0.1);       // x1 sits on its lower bound 1
  // NLopt has no multipliers: it empties them rather than leave another solver's behind.
  SolveResult reused = r;
  NloptSolver().Solve(p, &reused);
  CHECK(reused.nonlinear_duals.size() == 0);
}

TEST_CASE("Ipopt warm-started from a solution's multipliers re-solves a nearby problem in fewer iterations",
          "[nonlinear]") {
  // The same options for both starts: a small barrier and pushes, as a re-solve from a solution uses.
  IpoptSettings s;
  s.numeric_options["mu_init"] = 1e-6;
  s.numeric_options["bound_push"] = 1e-8;
  s.numeric_options["bound_frac"] = 1e-8;
  s.numeric_options["warm_start_bound_push"] = 1e-8;
  s.numeric_options["warm_start_bound_frac"] = 1e-8;
  s.numeric_options["warm_start_slack_bound_push"] = 1e-8;
  s.numeric_options["warm_start_slack_bound_frac"] = 1e-8;
  s.numeric_options["warm_start_mult_bound_push"] = 1e-8;
  const SolveResult first = IpoptSolver(s).Solve(Hs71());
  REQUIRE(first.status == SolveStatus::kSolved);
  // The next problem: the product's bound moved from 25 to 25.5, started at the old solution.
  Program next = Hs71(25.5);
  next.MutableInitialGuess() = first.x;
  const SolveResult reference = IpoptSolver().Solve(next);
  IpoptSolver primal(s);
  const SolveResult from_x = primal.Solve(next);
  IpoptSolver warm(s);
  warm.SetDualGuess({first.row_duals, first.nonlinear_duals, first.bound_duals});
  REQUIRE(warm.has_dual_guess());
  const SolveResult from_duals = warm.Solve(next);
  REQUIRE(reference.status == SolveStatus::kSolved);
  REQUIRE(from_x.status == SolveStatus::kSolved);
  REQUIRE(from_duals.status == SolveStatus::kSolved);
  INFO("iterations: from x alone " << from_x.info.iterations << ", with multipliers " << from_duals.info.iterations);
  CHECK(from_duals.objective == Approx(reference.objective).epsilon(1e-7));
  CHECK(from_duals.info.iterations < from_x.info.iterations);
  // Cleared, the solver starts from x alone again.
  warm.ClearDualGuess();
  CHECK(warm.Solve(next).info.iterations == from_x.info.iterations);
}

TEST_CASE("an Ipopt dual guess not sized to the program names its field", "[nonlinear]") {
  const Program p = Hs71();
  IpoptSolver ipopt;
  ipopt.SetDualGuess({Eigen::VectorXd(), Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(4)});
  CHECK_THROWS_WITH(ipopt.Solve(p), Catch::Contains("nonlinear_duals"));
  ipopt.SetDualGuess({Eigen::VectorXd(), Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(3)});
  CHECK_THROWS_WITH(ipopt.Solve(p), Catch::Contains("bound_duals"));
  ipopt.SetDualGuess({Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(4)});
  CHECK_THROWS_WITH(ipopt.Solve(p), Catch::Contains("row_duals"));
}

TEST_CASE("Ipopt's time limit holds on every solve, not only the first", "[nonlinear]") {
  IpoptSettings s;
  s.time_limit_s = 1e-6;
  IpoptSolver ipopt(s);
  for (int k = 0; k < 3; ++k) {
    const SolveResult r = ipopt.Solve(Hs100());
    INFO("solve " << k);
    CHECK(r.status == SolveStatus::kTimeLimit);
  }
  s.time_limit_s = 10;
  IpoptSolver relaxed(s);
  CHECK(relaxed.Solve(Hs100()).status == SolveStatus::kSolved);
  CHECK(relaxed.Solve(Hs100()).status == SolveStatus::kSolved);
}

TEST_CASE("Ipopt options pass through and a bad option is invalid input", "[nonlinear]") {
  IpoptSettings s;
  s.integer_options["max_iter"] = 2;
  CHECK(IpoptSolver(s).Solve(Hs100()).status == SolveStatus::kIterationLimit);
  IpoptSettings bad;
  bad.string_options["no_such_option"] = "yes";
  CHECK(IpoptSolver(bad).Solve(Hs71()).status == SolveStatus::kInvalidInput);
}

TEST_CASE("costs and constraints over several blocks map their Jacobians to the right columns", "[nonlinear]") {
  // Blocks a (2) and b (2); the constraint uses a[0] and b[1] only, a linear row couples a[1], b[0].
  // min |a - (1, 2)|^2 + |b - (0, 1)|^2 s.t. a0^2 + b1^2 <= 1, a1 + b0 = 1.
  // Optimum: the disc constraint pulls (a0, b1) from (1, 1) to (1/sqrt2, 1/sqrt2); the row gives
  // a1 = 1.5, b0 = -0.5. Objective 2 (1 - 1/sqrt2)^2 + 0.5.
  Program p;
  const VariableBlock a = p.AddVariables("a", 2);
  const VariableBlock b = p.AddVariables("b", 2);
  p.AddNonlinearCost({"distance", {a, b},
                      [a, b](const Eigen::VectorXd& x) {
                        return (a.Of(x) - Eigen::Vector2d(1, 2)).squaredNorm() + (b.Of(x) - Eigen::Vector2d(0, 1)).squaredNorm();
                      },
                      [a, b](const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::VectorXd> g) {
                        g = block == 0 ? Eigen::VectorXd(2 * (a.Of(x) - Eigen::Vector2d(1, 2)))
                                       : Eigen::VectorXd(2 * (b.Of(x) - Eigen::Vector2d(0, 1)));
                      }});
  NonlinearConstraint disc;
  disc.name = "disc";
  disc.blocks = {b, a};  // deliberately not in variable order
  disc.lower = Eigen::VectorXd::Constant(1, -kInf);
  disc.upper = Eigen::VectorXd::Constant(1, 1.0);
  disc.value = [a, b](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> out) {
    out[0] = a.Of(x)[0] * a.Of(x)[0] + b.Of(x)[1] * b.Of(x)[1];
  };
  disc.jacobian = [a, b](const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::MatrixXd> J) {
    if (block == 0) J << 0, 2 * b.Of(x)[1];  // d/db
    else J << 2 * a.Of(x)[0], 0;            // d/da
  };
  p.AddNonlinearConstraint(disc);
  p.AddLinearConstraint({{a, Eigen::RowVector2d(0, 1)}, {b, Eigen::RowVector2d(1, 0)}}, Eigen::VectorXd::Ones(1),
                        Eigen::VectorXd::Ones(1), "couple");
  const double s = 1.0 / std::sqrt(2.0);
  const double expected = 2 * (1 - s) * (1 - s) + 0.5;
  for (int which = 0; which < 2; ++which) {
    std::unique_ptr<Solver> solver = which == 0 ? MakeSolver("ipopt") : MakeSolver("nlopt");
    const SolveResult r = solver->Solve(p);
    INFO(solver->name());
    REQUIRE(r.status == SolveStatus::kSolved);
    CHECK(r.objective == Approx(expected).epsilon(1e-6));
    // SLSQP stops on the objective's progress, so its x is less exact than Ipopt's.
    const double tol = which == 0 ? 1e-6 : 1e-3;
    CHECK(r.x[0] == Approx(s).margin(tol));
    CHECK(r.x[1] == Approx(1.5).margin(tol));
    CHECK(r.x[2] == Approx(-0.5).margin(tol));
    CHECK(r.x[3] == Approx(s).margin(tol));
  }
}

namespace {

// Rosenbrock on the unit disc, x and y in blocks of their own so that the cost's Hessian has an
// off-diagonal block pair and the constraint lists its blocks out of variable order.
// min (1 - x)^2 + 100 (y - x^2)^2 s.t. x^2 + y^2 <= 1: on the circle at angle 0.6668 rad.
constexpr double kDiscX = 0.7864151540802091, kDiscY = 0.6176983126357081, kDiscF = 0.04567480871950024;

Program RosenbrockOnDisc(bool with_hessians, int* hessian_calls) {
  Program p;
  const VariableBlock x = p.AddVariables("x", 1);
  const VariableBlock y = p.AddVariables("y", 1);
  p.SetInitialGuess(x, Eigen::VectorXd::Constant(1, -0.5));
  p.SetInitialGuess(y, Eigen::VectorXd::Constant(1, 0.5));
  NonlinearCost f;
  f.name = "rosenbrock";
  f.blocks = {x, y};
  f.value = [](const Eigen::VectorXd& v) { return std::pow(1 - v[0], 2) + 100 * std::pow(v[1] - v[0] * v[0], 2); };
  f.gradient = [](const Eigen::VectorXd& v, int block, Eigen::Ref<Eigen::VectorXd> g) {
    g[0] = block == 0 ? -2 * (1 - v[0]) - 400 * v[0] * (v[1] - v[0] * v[0]) : 200 * (v[1] - v[0] * v[0]);
  };
  NonlinearConstraint disc;
  disc.name = "disc";
  disc.blocks = {y, x};
  disc.lower = Eigen::VectorXd::Constant(1, -kInf);
  disc.upper = Eigen::VectorXd::Constant(1, 1.0);
  disc.value = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::VectorXd> out) { out[0] = v.squaredNorm(); };
  disc.jacobian = [](const Eigen::VectorXd& v, int block, Eigen::Ref<Eigen::MatrixXd> J) {
    J(0, 0) = 2 * v[block == 0 ? 1 : 0];
  };
  if (with_hessians) {
    // Pairs left empty: every pair, (x, x), (y, x) and (y, y).
    f.hessian = [hessian_calls](const Eigen::VectorXd& v, int a, int b, Eigen::Ref<Eigen::MatrixXd> h) {
      ++*hessian_calls;
      if (a == 0 && b == 0) h(0, 0) = 2 - 400 * (v[1] - 3 * v[0] * v[0]);
      if (a == 1 && b == 0) h(0, 0) = -400 * v[0];
      if (a == 1 && b == 1) h(0, 0) = 200;
    };
    disc.hessian = [hessian_calls](const Eigen::VectorXd&, const Eigen::Ref<const Eigen::VectorXd>& w, int, int,
                                   Eigen::Ref<Eigen::MatrixXd> h) {
      ++*hessian_calls;
      h(0, 0) = 2 * w[0];
    };
    disc.hessian_pairs = {{0, 0}, {1, 1}};  // no cross term
  }
  p.AddNonlinearCost(f);
  p.AddNonlinearConstraint(disc);
  return p;
}

}  // namespace

TEST_CASE("Ipopt uses the nonlinear parts' exact Hessians when every part has one", "[nonlinear]") {
  int calls = 0;
  const Program exact = RosenbrockOnDisc(true, &calls);
  REQUIRE(exact.HasHessians());
  const SolveResult newton = IpoptSolver().Solve(exact);
  REQUIRE(newton.status == SolveStatus::kSolved);
  CHECK(calls > 0);
  CHECK(newton.x[0] == Approx(kDiscX).margin(1e-7));
  CHECK(newton.x[1] == Approx(kDiscY).margin(1e-7));
  CHECK(newton.objective == Approx(kDiscF).epsilon(1e-7));
  // The same program with the Hessians ignored, and without them: quasi-Newton, same optimum,
  // more iterations (a wrong Hessian would cost Newton its fast convergence).
  IpoptSettings quasi;
  quasi.exact_hessian_for_nlp = false;
  calls = 0;
  const SolveResult lbfgs = IpoptSolver(quasi).Solve(exact);
  CHECK(calls == 0);
  int unused = 0;
  const Program plain = RosenbrockOnDisc(false, &unused);
  CHECK_FALSE(plain.HasHessians());
  const SolveResult without = IpoptSolver().Solve(plain);
  for (const SolveResult* r : {&lbfgs, &without}) {
    REQUIRE(r->status == SolveStatus::kSolved);
    CHECK(r->objective == Approx(kDiscF).epsilon(1e-6));
  }
  INFO("iterations: exact " << newton.info.iterations << ", limited-memory " << lbfgs.info.iterations);
  CHECK(without.info.iterations == lbfgs.info.iterations);
  CHECK(newton.info.iterations < lbfgs.info.iterations);
}

TEST_CASE("NLopt's Hessian scaling reaches the same optimum of a badly scaled problem in fewer evaluations",
          "[nonlinear]") {
  // min 1e4 (x - 1)^2 + 1e3 (y - 2)^2 + 1e3 (y - 2)^4 s.t. x + y >= 3.5: curvatures 2e4 and 2e3
  // (the quadratic part and a nonlinear cost's Hessian). With v = y - 2: 2v^3 + 11v - 5 = 0.
  Program p;
  const VariableBlock x = p.AddVariables("x", 1);
  const VariableBlock y = p.AddVariables("y", 1);
  p.AddQuadraticCost(x, Eigen::MatrixXd::Constant(1, 1, 2e4), Eigen::VectorXd::Constant(1, -2e4));
  p.AddConstant(1e4);
  NonlinearCost quartic;
  quartic.name = "quartic";
  quartic.blocks = {y};
  quartic.value = [](const Eigen::VectorXd& v) { return 1e3 * std::pow(v[1] - 2, 2) + 1e3 * std::pow(v[1] - 2, 4); };
  quartic.gradient = [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::VectorXd> g) {
    g[0] = 2e3 * (v[1] - 2) + 4e3 * std::pow(v[1] - 2, 3);
  };
  quartic.hessian = [](const Eigen::VectorXd& v, int, int, Eigen::Ref<Eigen::MatrixXd> h) {
    h(0, 0) = 2e3 + 12e3 * std::pow(v[1] - 2, 2);
  };
  p.AddNonlinearCost(quartic);
  p.AddLinearConstraint({{x, Eigen::MatrixXd::Ones(1, 1)}, {y, Eigen::MatrixXd::Ones(1, 1)}}, Eigen::VectorXd::Constant(1, 3.5),
                        Eigen::VectorXd::Constant(1, kInf), "sum");
  p.SetInitialGuess(x, Eigen::VectorXd::Constant(1, 3.0));
  p.SetInitialGuess(y, Eigen::VectorXd::Constant(1, -1.0));
  NloptSettings plain, scaled;
  scaled.scale_by_hessian = true;
  const SolveResult a = NloptSolver(plain).Solve(p);
  const SolveResult b = NloptSolver(scaled).Solve(p);
  INFO("evaluations: plain " << a.info.iterations << ", scaled " << b.info.iterations);
  for (const SolveResult* r : {&a, &b}) {
    REQUIRE(r->status == SolveStatus::kSolved);
    CHECK(r->x[0] == Approx(1.0608526771308044).margin(1e-5));
    CHECK(r->x[1] == Approx(2.4391473228691956).margin(1e-5));
    CHECK(r->objective == Approx(267.07211998853165).epsilon(1e-5));  // within SLSQP's 1e-6 constraint tolerance
  }
  CHECK(b.info.iterations < a.info.iterations);
}
