#include "stairplan/planning/body/plan_body.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "stairplan/planning/body/body_check.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/plan_gait.h"

namespace stairplan {
namespace {

// The body moved less than this between its last two samples, in every coordinate (pitch times a
// 1 m lever) [m]: it stands.
constexpr double kRestStep = 1e-4;

bool AtRest(const std::vector<BodyState>& body) {
  if (body.size() < 2) return false;
  const BodyState& a = body[body.size() - 2];
  const BodyState& b = body.back();
  return std::abs(b.x - a.x) < kRestStep && std::abs(b.y - a.y) < kRestStep && std::abs(b.z - a.z) < kRestStep &&
         std::abs(b.pitch - a.pitch) < kRestStep;
}

}  // namespace

BodyCheckMargins RecheckMargins(const BodyPlannerSettings& settings, const std::optional<Gait>& gait) {
  BodyCheckMargins margins;
  margins.clearance = settings.clearance_margin;
  if (settings.stability_margin >= 0.0 && gait && IsQuasiStatic(*gait)) margins.stability = settings.checked_stability_margin;
  if (settings.stance_rows) margins.retreat = settings.max_retreat;
  return margins;
}

Plan PlanBody(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, Plan plan,
              const BodyPlannerSettings& settings, const std::optional<Eigen::Vector2d>& standing_xy,
              bool stop_at_first_violation) {
  settings.Validate();
  if (plan.status != PlanStatus::kOk) return plan;
  return PlanBody(RobotKinematics(robot), stairs, map, std::move(plan), settings, standing_xy, stop_at_first_violation);
}

Plan PlanBody(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map, Plan plan,
              const BodyPlannerSettings& settings, const std::optional<Eigen::Vector2d>& standing_xy,
              bool stop_at_first_violation) {
  settings.Validate();
  if (plan.status != PlanStatus::kOk) return plan;
  const RobotModel& robot = kinematics.robot();
  const auto start = std::chrono::steady_clock::now();
  // Offline there is no cycle budget: every cycle solves (and fills the bound caches it needs).
  BodyPlannerSettings offline = settings;
  offline.cycle_budget_s = 10.0;
  BodyPlanner planner(kinematics, stairs, map, plan, offline);
  const double end = planner.schedule().end_time();
  const double dt = settings.knot_dt;
  const int cycles = static_cast<int>(std::ceil(end / dt - 1e-9));
  // After the last touchdown the loop runs on, at most a horizon, until the body stands still:
  // a plan that ends while the body moves asks the robot to stop it at once.
  const int settle_cycles = settings.knots;
  std::vector<BodyState> body;
  body.reserve(static_cast<std::size_t>(cycles + settle_cycles) + 1);
  plan.body_cycles.clear();
  plan.body_cycles.reserve(static_cast<std::size_t>(cycles + settle_cycles) + 1);
  BodyState state = standing_xy ? planner.StartStateAt(*standing_xy) : planner.StartState();
  // Cycles whose next knot had no valid body height under the (conservative, linearised) bounds.
  int conflict_cycles = 0, stale_cycles = 0;
  std::string first_conflict, solver_failure;
  // The plan stands or falls by the exact re-check: the cached bounds are conservative, so a
  // cycle may report a conflict the exact kinematics do not have.
  auto& bounds = static_cast<KinematicBodyBounds&>(planner.bounds());
  BodyChecker checker(bounds, planner.schedule(), RecheckMargins(settings, plan.gait));
  BodyPlanCheck check;
  // Cycle c's time: on the knots up to the flight's end, then from the end on.
  const auto time_of = [&](int c) { return c < cycles ? c * dt : end + (c - cycles) * dt; };
  for (int c = 0; c <= cycles + settle_cycles; ++c) {
    const double now = time_of(c);
    const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
    if (out.status == BodyPlanStatus::kStale) {
      ++stale_cycles;  // the shifted previous plan: still a valid plan
    } else if (out.status == BodyPlanStatus::kInfeasible) {
      char text[200];
      if (out.solve_status != optim::SolveStatus::kSolved) {
        std::snprintf(text, sizeof(text), "body planner: QP %s at t=%.3f s",
                      std::string(optim::ToString(out.solve_status)).c_str(), now);
        if (solver_failure.empty()) solver_failure = text;
      } else if (conflict_cycles++ == 0) {
        std::snprintf(text, sizeof(text), "no valid body height for leg %s at t=%.3f s",
                      robot.legs()[static_cast<std::size_t>(out.conflict_leg)].name.c_str(), now + dt);
        first_conflict = text;
      }
    }
    plan.body_cycles.push_back(
        {now, out.status, out.solves, out.iterations, out.timings.solve_us, out.timings.total_us, out.relaxation});
    body.push_back(out.knots[0]);
    body.back().t = now;
    if (stop_at_first_violation) {
      checker.CheckSample(body, body.size() - 1, check);
      if (!check.ok() || !solver_failure.empty()) break;
    }
    if (c >= cycles && AtRest(body)) break;
    state = planner.Interpolate(time_of(c + 1));
  }
  plan.body = std::move(body);
  plan.body_planner = BodyPlannerKind::kRecedingHorizonQp;
  const double plan_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  if (!stop_at_first_violation) check = checker.CheckTrajectory(plan.body);
  std::string reason = solver_failure;
  if (reason.empty() && !check.ok()) {
    reason = "body re-check: " + check.Summary() + " (" + std::to_string(check.violations) +
             (check.violations == 1 ? " violation" : " violations");
    if (conflict_cycles > 0) reason += "; " + std::to_string(conflict_cycles) + " cycles found " + first_conflict;
    if (stale_cycles > 0) reason += "; " + std::to_string(stale_cycles) + " cycles kept the previous plan";
    reason += ")";
  }
  if (!reason.empty()) {
    plan.status = PlanStatus::kInfeasible;
    plan.status_reason = reason;
  }
  plan.timing_us.emplace_back("body", plan_us);
  return plan;
}

}  // namespace stairplan
