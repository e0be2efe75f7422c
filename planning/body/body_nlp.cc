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

  optim::Program prog;
  const optim::VariableBlock zb = prog.AddVariables("height", n);
  const optim::VariableBlock pb = prog.AddVariables("pitch", n);
  const optim::VariableBlock sb = prog.AddVariables("com_shift", n);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd d1 = FirstDifferences(n), d2 = SecondDifferences(n);
  const Eigen::MatrixXd smooth = 2.0 * set.velocity_weight / (dt * dt) * d1.transpose() * d1 +
                                 2.0 * set.acceleration_weight / (dt * dt * dt * dt) * d2.transpose() * d2;
  prog.AddQuadraticCost(zb, smooth, Eigen::VectorXd::Zero(n));
  prog.AddQuadraticCost(pb, 2.0 * set.pitch_weight * identity + smooth, -2.0 * set.pitch_weight * pitch_ref);
  prog.AddQuadraticCost(sb, 2.0 * set.shift_weight * identity + smooth, -2.0 * set.shift_weight * shift_ref);
  prog.AddConstant(set.pitch_weight * pitch_ref.squaredNorm() + set.shift_weight * shift_ref.squaredNorm());
  const Eigen::MatrixXd zeros = Eigen::MatrixXd::Zero(n - 2, n);
  Eigen::MatrixXd accel_z(3 * (n - 2), n), accel_p(3 * (n - 2), n), accel_s(3 * (n - 2), n);
  accel_z << d2, zeros, zeros;
  accel_p << zeros, d2, zeros;
  accel_s << zeros, zeros, d2;
  Eigen::VectorXd accel_hi(3 * (n - 2));
  accel_hi << Eigen::VectorXd::Constant(n - 2, set.max_height_accel * dt * dt),
      Eigen::VectorXd::Constant(n - 2, set.max_pitch_accel * dt * dt),
      Eigen::VectorXd::Constant(n - 2, set.max_shift_accel * dt * dt);
  prog.AddLinearConstraint({{zb, accel_z}, {pb, accel_p}, {sb, accel_s}}, -accel_hi, accel_hi, "acceleration");

  Eigen::VectorXd z_lo = Eigen::VectorXd::Constant(n, -optim::kInf), z_hi = -z_lo;
  Eigen::VectorXd p_lo = Eigen::VectorXd::Constant(n, -set.max_pitch), p_hi = -p_lo;
  Eigen::VectorXd s_lo = Eigen::VectorXd::Constant(n, -set.max_shift), s_hi = -s_lo;
  z_lo[0] = z_hi[0] = guess[0].z;
  p_lo[0] = p_hi[0] = guess[0].pitch;
  s_lo[0] = s_hi[0] = guess[0].com_shift;
  prog.SetVariableBounds(zb, z_lo, z_hi);
  prog.SetVariableBounds(pb, p_lo, p_hi);
  prog.SetVariableBounds(sb, s_lo, s_hi);
  Eigen::VectorXd x0(3 * n);
  for (int k = 0; k < n; ++k) {
    x0[zb.start + k] = guess[static_cast<std::size_t>(k)].z;
    x0[pb.start + k] = guess[static_cast<std::size_t>(k)].pitch;
    x0[sb.start + k] = guess[static_cast<std::size_t>(k)].com_shift;
  }
  prog.MutableInitialGuess() = x0;

  // Exact hip heights: sum over knots and legs of w (z + hip_dz(pitch) - foot_z - wanted)^2.
  const double wh = set.height_weight;
  optim::NonlinearCost height;
  height.name = "hip_height";
  height.blocks = {zb, pb};
  height.value = [&, n](const Eigen::VectorXd& x) {
    double f = 0.0;
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < kBodyLegs; ++l) {
        const double r = x[zb.start + k] + planner.HipDz(l, x[pb.start + k]) - foot_z[k * kBodyLegs + l] - hip_height;
        f += wh * r * r;
      }
    }
    return f;
  };
  height.gradient = [&, n](const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::VectorXd> g) {
    for (int k = 0; k < n; ++k) {
      double sum = 0.0;
      for (int l = 0; l < kBodyLegs; ++l) {
        const double p = x[pb.start + k];
        const double r = x[zb.start + k] + planner.HipDz(l, p) - foot_z[k * kBodyLegs + l] - hip_height;
        const Eigen::Vector3d& h = planner.hip_B(l);
        sum += 2.0 * wh * r * (block == 0 ? 1.0 : -std::cos(p) * h.x() - std::sin(p) * h.z());
      }
      g[k] = sum;
    }
  };
  prog.AddNonlinearCost(height);

  // Each stance row: (hip height - lowest valid) >= 0 and (highest valid - hip height) >= 0, the
  // bounds at the exact hip offset and pitch.
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
  const int m = static_cast<int>(rows.size());
  if (m > 0) {
    optim::NonlinearConstraint limits;
    limits.name = "hip_bounds";
    limits.blocks = {zb, pb, sb};
    limits.lower = Eigen::VectorXd::Zero(2 * m);
    limits.upper = Eigen::VectorXd::Constant(2 * m, optim::kInf);
    limits.value = [&, m](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> c) {
      for (int i = 0; i < m; ++i) {
        const StanceRow& r = rows[static_cast<std::size_t>(i)];
        c.segment<2>(2 * i) = margins(r, x[zb.start + r.knot], x[pb.start + r.knot], x[sb.start + r.knot]);
      }
    };
    limits.jacobian = [&, m](const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::MatrixXd> jac) {
      jac.setZero();
      for (int i = 0; i < m; ++i) {
        const StanceRow& r = rows[static_cast<std::size_t>(i)];
        const double z = x[zb.start + r.knot], p = x[pb.start + r.knot], s = x[sb.start + r.knot];
        Eigen::Vector2d d;
        if (block == 0) {
          d = Eigen::Vector2d(1.0, -1.0);
        } else if (block == 1) {
          d = (margins(r, z, p + kFiniteStep, s) - margins(r, z, p - kFiniteStep, s)) / (2.0 * kFiniteStep);
        } else {
          d = (margins(r, z, p, s + kFiniteStep) - margins(r, z, p, s - kFiniteStep)) / (2.0 * kFiniteStep);
        }
        jac(2 * i, r.knot) = d[0];
        jac(2 * i + 1, r.knot) = d[1];
      }
    };
    prog.AddNonlinearConstraint(limits);
  }

  const auto bound_distance = [&](const Eigen::VectorXd& x) {
    double worst = std::numeric_limits<double>::infinity();
    for (const StanceRow& r : rows) {
      worst = std::min(worst, margins(r, x[zb.start + r.knot], x[pb.start + r.knot], x[sb.start + r.knot]).minCoeff());
    }
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
    b.z = x[zb.start + k];
    b.pitch = x[pb.start + k];
    b.com_shift = x[sb.start + k];
    b.x = neutral_x[k] + heading * b.com_shift;
    b.y = neutral_y[k];
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
