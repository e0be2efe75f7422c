#include "planning/body/body_nlp.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "planning/body/kinematic_body_bounds.h"
#include "planning/optim/ipopt_solver.h"
#include "planning/optim/nlopt_solver.h"
#include "planning/optim/program.h"

namespace stairplan {
namespace {

// Finite-difference step of the tabulated bounds' derivatives [m or rad].
constexpr double kFiniteStep = 1e-5;

struct StanceRow {
  int knot = 0, leg = 0, foothold = 0;
  double contact_x = 0.0, contact_z = 0.0;
};

Eigen::MatrixXd FirstDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 1, n);
  for (int k = 0; k + 1 < n; ++k) d(k, k) = -1.0, d(k, k + 1) = 1.0;
  return d;
}

Eigen::MatrixXd SecondDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 2, n);
  for (int k = 0; k + 2 < n; ++k) d(k, k) = 1.0, d(k, k + 1) = -2.0, d(k, k + 2) = 1.0;
  return d;
}

// The NLP over knots t0 + k dt with `guess` as the initial point (knot 0 pinned to it).
BodyNlpWindow SolveWindow(BodyPlanner& planner, const BodyNlpSettings& ns, double t0,
                          const std::vector<BodyState>& guess, std::vector<BodyState>* out) {
  const BodyPlannerSettings& set = planner.settings();
  const FootSchedule& schedule = planner.schedule();
  BodyBounds& bounds = planner.bounds();
  const int n = static_cast<int>(guess.size());
  const double dt = set.knot_dt, heading = schedule.heading();
  const double hip_height = planner.desired_hip_height();

  // Per knot: the neutral body, the references, the feet's heights and the stance rows.
  Eigen::VectorXd neutral_x(n), neutral_y(n), pitch_ref(n), shift_ref(n), foot_z(n * kBodyLegs);
  std::vector<StanceRow> rows;
  for (int k = 0; k < n; ++k) {
    const double t = t0 + k * dt;
    const Eigen::Vector2d xy = schedule.NeutralBodyXY(t);
    neutral_x[k] = xy.x();
    neutral_y[k] = xy.y();
    const double feet_pitch = schedule.FeetPitch(t);
    pitch_ref[k] = std::clamp(feet_pitch, -set.max_pitch, set.max_pitch);
    const double stairness =
        planner.stairs_pitch() > 0.0 ? std::clamp(std::abs(feet_pitch) / planner.stairs_pitch(), 0.0, 1.0) : 0.0;
    shift_ref[k] = set.stairs_com_shift * stairness;
    for (int l = 0; l < kBodyLegs; ++l) {
      const LegPhase phase = schedule.Phase(l, t);
      foot_z[k * kBodyLegs + l] = phase.foot_W.z();
      if (k == 0 || !phase.stance) continue;
      const Eigen::Vector3d& c = schedule.footholds()[static_cast<std::size_t>(phase.foothold)].contact_W;
      rows.push_back({k, l, phase.foothold, c.x(), c.z()});
    }
  }

  // One variable block per knot, [z, pitch, shift]: each knot's constraints then touch only its
  // own block, so the solvers see a sparse Jacobian instead of a dense one.
  optim::Program prog;
  std::vector<optim::VariableBlock> knot_blocks;
  for (int k = 0; k < n; ++k) knot_blocks.push_back(prog.AddVariables("knot" + std::to_string(k), 3));
  const auto Z = [](int k) { return 3 * k; };
  const auto P = [](int k) { return 3 * k + 1; };
  const auto S = [](int k) { return 3 * k + 2; };
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd d1 = FirstDifferences(n), d2 = SecondDifferences(n);
  const Eigen::MatrixXd smooth = 2.0 * set.velocity_weight / (dt * dt) * d1.transpose() * d1 +
                                 2.0 * set.acceleration_weight / (dt * dt * dt * dt) * d2.transpose() * d2;
  const Eigen::MatrixXd hp = 2.0 * set.pitch_weight * identity + smooth;
  const Eigen::MatrixXd hs = 2.0 * set.shift_weight * identity + smooth;
  Eigen::MatrixXd& hessian = prog.MutableHessian();
  Eigen::VectorXd& linear = prog.MutableLinearCost();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      hessian(Z(i), Z(j)) = smooth(i, j);
      hessian(P(i), P(j)) = hp(i, j);
      hessian(S(i), S(j)) = hs(i, j);
    }
    linear[P(i)] = -2.0 * set.pitch_weight * pitch_ref[i];
    linear[S(i)] = -2.0 * set.shift_weight * shift_ref[i];
  }
  prog.AddConstant(set.pitch_weight * pitch_ref.squaredNorm() + set.shift_weight * shift_ref.squaredNorm());
  // Acceleration limits: rows (quantity, k) over knots k .. k + 2.
  {
    const int rows_per = n - 2;
    std::vector<optim::LinearTerm> terms;
    for (int k = 0; k < n; ++k) terms.emplace_back(knot_blocks[static_cast<std::size_t>(k)], Eigen::MatrixXd::Zero(3 * rows_per, 3));
    for (int q = 0; q < 3; ++q) {
      for (int r = 0; r < rows_per; ++r) {
        terms[static_cast<std::size_t>(r)].second(q * rows_per + r, q) = 1.0;
        terms[static_cast<std::size_t>(r + 1)].second(q * rows_per + r, q) = -2.0;
        terms[static_cast<std::size_t>(r + 2)].second(q * rows_per + r, q) = 1.0;
      }
    }
    Eigen::VectorXd accel_hi(3 * rows_per);
    accel_hi << Eigen::VectorXd::Constant(rows_per, set.max_height_accel * dt * dt),
        Eigen::VectorXd::Constant(rows_per, set.max_pitch_accel * dt * dt),
        Eigen::VectorXd::Constant(rows_per, set.max_shift_accel * dt * dt);
    prog.AddLinearConstraint(terms, -accel_hi, accel_hi, "acceleration");
  }
  Eigen::VectorXd x0(3 * n);
  for (int k = 0; k < n; ++k) {
    const BodyState& g = guess[static_cast<std::size_t>(k)];
    x0.segment<3>(Z(k)) << g.z, g.pitch, g.com_shift;
    Eigen::Vector3d lo(-optim::kInf, -set.max_pitch, -set.max_shift), hi = -lo;
    if (k == 0) lo = hi = x0.segment<3>(0);  // knot 0 is the state
    prog.SetVariableBounds(knot_blocks[static_cast<std::size_t>(k)], lo, hi);
  }
  prog.MutableInitialGuess() = x0;

  // Exact hip heights: sum over knots and legs of w (z + hip_dz(pitch) - foot_z - wanted)^2.
  const double wh = set.height_weight;
  optim::NonlinearCost height;
  height.name = "hip_height";
  height.blocks = knot_blocks;
  height.value = [&, n](const Eigen::VectorXd& x) {
    double f = 0.0;
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < kBodyLegs; ++l) {
        const double r = x[Z(k)] + planner.HipDz(l, x[P(k)]) - foot_z[k * kBodyLegs + l] - hip_height;
        f += wh * r * r;
      }
    }
    return f;
  };
  height.gradient = [&](const Eigen::VectorXd& x, int k, Eigen::Ref<Eigen::VectorXd> g) {
    g.setZero();
    const double p = x[P(k)];
    for (int l = 0; l < kBodyLegs; ++l) {
      const double r = x[Z(k)] + planner.HipDz(l, p) - foot_z[k * kBodyLegs + l] - hip_height;
      const Eigen::Vector3d& h = planner.hip_B(l);
      g[0] += 2.0 * wh * r;
      g[1] += 2.0 * wh * r * (-std::cos(p) * h.x() - std::sin(p) * h.z());
    }
  };
  prog.AddNonlinearCost(height);

  // Each stance row: (hip height - lowest valid) >= 0 and (highest valid - hip height) >= 0, the
  // bounds at the exact hip offset and pitch; one constraint per knot, on that knot's block.
  const auto margins = [&](const StanceRow& r, double z, double p, double s) {
    const double h = z + planner.HipDz(r.leg, p) - r.contact_z;
    HipBox box;
    box.leg = r.leg;
    box.foothold = r.foothold;
    box.dx_lo = box.dx_hi = heading * (neutral_x[r.knot] - r.contact_x) + s + planner.HipDx(r.leg, p);
    box.pitch_lo = box.pitch_hi = p;
    const HeightRange range = bounds.HipHeight(box);
    if (range.empty()) return Eigen::Vector2d(-1.0, -1.0);  // no valid height here
    return Eigen::Vector2d(h - range.lo, range.hi - h);
  };
  for (std::size_t first = 0; first < rows.size();) {
    std::size_t last = first;
    while (last < rows.size() && rows[last].knot == rows[first].knot) ++last;
    const int k = rows[first].knot, m = static_cast<int>(last - first);
    optim::NonlinearConstraint limits;
    limits.name = "hip_bounds" + std::to_string(k);
    limits.blocks = {knot_blocks[static_cast<std::size_t>(k)]};
    limits.lower = Eigen::VectorXd::Zero(2 * m);
    limits.upper = Eigen::VectorXd::Constant(2 * m, optim::kInf);
    limits.value = [&, first, m, k](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> c) {
      for (int i = 0; i < m; ++i) c.segment<2>(2 * i) = margins(rows[first + static_cast<std::size_t>(i)], x[Z(k)], x[P(k)], x[S(k)]);
    };
    limits.jacobian = [&, first, m, k](const Eigen::VectorXd& x, int, Eigen::Ref<Eigen::MatrixXd> jac) {
      const double z = x[Z(k)], p = x[P(k)], s = x[S(k)];
      for (int i = 0; i < m; ++i) {
        const StanceRow& r = rows[first + static_cast<std::size_t>(i)];
        const Eigen::Vector2d dp = (margins(r, z, p + kFiniteStep, s) - margins(r, z, p - kFiniteStep, s)) / (2.0 * kFiniteStep);
        const Eigen::Vector2d ds = (margins(r, z, p, s + kFiniteStep) - margins(r, z, p, s - kFiniteStep)) / (2.0 * kFiniteStep);
        jac.row(2 * i) << 1.0, dp[0], ds[0];
        jac.row(2 * i + 1) << -1.0, dp[1], ds[1];
      }
    };
    prog.AddNonlinearConstraint(limits);
    first = last;
  }

  const auto bound_distance = [&](const Eigen::VectorXd& x) {
    double worst = std::numeric_limits<double>::infinity();
    for (const StanceRow& r : rows) worst = std::min(worst, margins(r, x[Z(r.knot)], x[P(r.knot)], x[S(r.knot)]).minCoeff());
    return worst;
  };

  BodyNlpWindow window;
  window.qp_objective = prog.Objective(x0);
  window.qp_bound_distance = bound_distance(x0);
  optim::SolveResult result;
  const auto start = std::chrono::steady_clock::now();
  if (ns.solver == "nlopt") {
    optim::NloptSettings s;
    s.xtol_rel = ns.tolerance * 1e-2;
    s.ftol_rel = ns.tolerance * 1e-4;
    s.constraint_tol = 1e-7;
    s.max_evaluations = ns.max_iterations * 20;
    optim::NloptSolver solver(s);
    solver.Solve(prog, &result);
  } else {
    optim::IpoptSettings s;
    s.tolerance = ns.tolerance;
    s.max_iterations = ns.max_iterations;
    optim::IpoptSolver solver(s);
    solver.Solve(prog, &result);
  }
  window.solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  window.status = result.status;
  window.iterations = result.info.iterations;
  const Eigen::VectorXd& x = result.x.size() == x0.size() && result.x.allFinite() ? result.x : x0;
  window.nlp_objective = prog.Objective(x);
  window.nlp_bound_distance = bound_distance(x);
  out->resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    BodyState& b = (*out)[static_cast<std::size_t>(k)];
    b.t = t0 + k * dt;
    b.z = x[Z(k)];
    b.pitch = x[P(k)];
    b.com_shift = x[S(k)];
    b.com_shift_y = guess[static_cast<std::size_t>(k)].com_shift_y;  // the QP's sideways shift is kept
    b.x = neutral_x[k] + heading * b.com_shift;
    b.y = neutral_y[k] + heading * b.com_shift_y;
    b.yaw = schedule.yaw();
  }
  return window;
}

}  // namespace

void BodyNlpSettings::Validate() const {
  if (solver != "ipopt" && solver != "nlopt") {
    throw std::invalid_argument("solver: must be 'ipopt' or 'nlopt' (got '" + solver + "')");
  }
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw std::invalid_argument("tolerance: must be in (0, 1)");
  if (max_iterations < 1) throw std::invalid_argument("max_iterations: must be positive");
}

BodyNlpWindow SolveBodyNlp(BodyPlanner& planner, const BodyNlpSettings& settings, double now,
                           std::vector<BodyState>* knots) {
  settings.Validate();
  return SolveWindow(planner, settings, now, planner.output().knots, knots);
}

BodyNlpWindow SolveBodyNlpFrom(BodyPlanner& planner, const BodyNlpSettings& settings, double t0,
                               const std::vector<BodyState>& guess, std::vector<BodyState>* knots) {
  settings.Validate();
  if (guess.size() < 3) throw std::invalid_argument("SolveBodyNlpFrom: guess needs at least 3 knots");
  return SolveWindow(planner, settings, t0, guess, knots);
}

Plan RefineBodyNlp(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, Plan plan,
                   const BodyPlannerSettings& settings, const BodyNlpSettings& nlp, BodyNlpWindow* summary) {
  settings.Validate();
  nlp.Validate();
  if (plan.status != PlanStatus::kOk && plan.status_reason.rfind("body", 0) != 0) return plan;  // no footsteps
  if (plan.body.size() < 3) return plan;
  const auto start = std::chrono::steady_clock::now();
  BodyPlanner planner(robot, stairs, map, plan, settings);
  const std::size_t window = static_cast<std::size_t>(settings.knots);
  BodyNlpWindow worst;
  worst.qp_bound_distance = worst.nlp_bound_distance = std::numeric_limits<double>::infinity();
  worst.status = optim::SolveStatus::kSolved;
  std::string failure;
  std::vector<BodyState> guess, solution;
  for (std::size_t i0 = 0; i0 + 1 < plan.body.size(); i0 += window - 1) {
    const std::size_t count = std::min(window, plan.body.size() - i0);
    if (count < 3) break;
    guess.assign(plan.body.begin() + static_cast<std::ptrdiff_t>(i0), plan.body.begin() + static_cast<std::ptrdiff_t>(i0 + count));
    const BodyNlpWindow w = SolveWindow(planner, nlp, guess.front().t, guess, &solution);
    worst.qp_objective += w.qp_objective;
    worst.nlp_objective += w.nlp_objective;
    worst.qp_bound_distance = std::min(worst.qp_bound_distance, w.qp_bound_distance);
    worst.nlp_bound_distance = std::min(worst.nlp_bound_distance, w.nlp_bound_distance);
    worst.solve_ms += w.solve_ms;
    worst.iterations += w.iterations;
    ++worst.windows;
    if (w.status != optim::SolveStatus::kSolved) worst.status = w.status;
    // A window's solution replaces the QP's only when it is solved, or at least inside the
    // bounds and cheaper (the kinks of the tabulated bounds can stall a solver at a good point);
    // otherwise the QP's values stay, so refining never makes a plan worse.
    const bool usable = w.status == optim::SolveStatus::kSolved ||
                        (w.nlp_bound_distance >= -1e-6 && w.nlp_objective <= w.qp_objective);
    if (!usable) continue;
    ++worst.windows_refined;
    for (std::size_t k = 0; k < count; ++k) plan.body[i0 + k] = solution[k];
  }
  auto& bounds = static_cast<KinematicBodyBounds&>(planner.bounds());
  const BodyPlanCheck check = CheckBodyTrajectory(bounds, planner.schedule(), plan.body, settings.clearance_margin);
  if (!check.ok()) failure = "body NLP re-check: " + check.first_violation;
  plan.status = failure.empty() ? PlanStatus::kOk : PlanStatus::kInfeasible;
  plan.status_reason = failure;
  plan.timing_us.emplace_back("body_nlp", std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  if (summary != nullptr) *summary = worst;
  return plan;
}

}  // namespace stairplan
