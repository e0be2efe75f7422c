#include "stairplan/planning/step/step_planner_driver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "stairplan/planning/step/step_height.h"
#include "stairplan/planning/step/step_planner.h"

namespace stairplan {
namespace {

std::string ControllerName(const FixedCadenceController& c) {
  std::ostringstream out;
  out << ToString(c.gait) << " " << c.cadence_s << " s";
  return out.str();
}

Plan MarkInfeasible(Plan plan, const std::string& reason) {
  plan.status = PlanStatus::kInfeasible;
  plan.status_reason = reason;
  return plan;
}

}  // namespace

Plan PlanWithStepPlanner(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                         const StepPlannerSettings& settings, std::shared_ptr<const ReachModel> reach) {
  settings.Validate();
  StepPlanner planner(robot, map, settings, std::move(reach));
  Plan plan;
  plan.robot_name = robot.name();
  plan.robot_source = robot.source();
  plan.facing = map.facing();
  for (const LegModel& leg : planner.legs()) plan.legs.push_back(leg.name);
  const auto& controllers = planner.controllers();
  for (const FixedCadenceController& c : controllers) {
    ControllerScore score;
    score.cadence_s = c.cadence_s;
    score.gait = c.gait;
    plan.controllers.push_back(score);
  }
  std::vector<double> score_sum(controllers.size(), 0.0);
  std::vector<int> admissible_cycles(controllers.size(), 0);
  const auto finish_scores = [&](Plan& p) {
    int best = -1;
    for (std::size_t i = 0; i < controllers.size(); ++i) {
      ControllerScore& s = p.controllers[i];
      s.score = admissible_cycles[i] > 0 ? score_sum[i] / admissible_cycles[i] : std::numeric_limits<double>::infinity();
      if (s.cycles_selected > 0 && (best < 0 || s.cycles_selected > p.controllers[static_cast<std::size_t>(best)].cycles_selected)) {
        best = static_cast<int>(i);
      }
    }
    p.selected = best;
    const FixedCadenceController& shown = controllers[static_cast<std::size_t>(std::max(0, best))];
    p.cadence_s = best >= 0 ? shown.cadence_s : 0.0;
    p.gait = best >= 0 ? std::optional<Gait>(shown.gait) : std::nullopt;
  };

  const int last = map.size() - 1;
  if (const auto rise = FirstRiseTooHigh(planner.legs(), map, settings)) return MarkInfeasible(plan, ToString(*rise));
  if (map.stair(0).step_region.empty()) return MarkInfeasible(plan, "the first surface has no step region to start on");
  // Start with the feet under the hips, the leading feet start_gap before the end of the first
  // step region.
  double region_hi = -std::numeric_limits<double>::infinity();
  for (const auto& v : map.stair(0).step_region.vertices) region_hi = std::max(region_hi, v.x());
  double lead = -std::numeric_limits<double>::infinity();
  for (int l = 0; l < 4; ++l) lead = std::max(lead, planner.NeutralFootXY(l, Eigen::Vector2d::Zero()).x());
  const Eigen::Vector2d body0(region_hi - settings.start_gap - lead, 0.0);
  const Eigen::Vector2d velocity(settings.speed, 0.0);

  StepPlannerInput input;
  input.velocity_W = velocity;
  for (int l = 0; l < 4; ++l) {
    const Eigen::Vector2d xy = planner.SnapIntoRegion(0, planner.NeutralFootXY(l, body0));
    StepLegState& leg = input.legs[static_cast<std::size_t>(l)];
    leg.foot_W = Eigen::Vector3d(xy.x(), xy.y(), map.stair(0).z);
    leg.stair = 0;
    leg.last_touchdown_s = 0.0;
    plan.initial_feet_W.push_back(leg.foot_W);
  }

  // The first swing waits settle_s: with four feet down the body moves forward, out of the line
  // between the diagonal feet that will carry it while the first leg swings.
  double t = settings.settle_s;
  bool arrived = false;
  std::string failure;
  for (int cycle = 0; cycle < settings.max_cycles; ++cycle) {
    input.now_s = t;
    input.body_xy_W = body0 + velocity * t;
    if (input.body_xy_W.x() + lead > stairs.x_max()) {
      failure = "the body ran past the end of the stairs (landing_after too short for the robot)";
      break;
    }
    const int chosen = planner.Update(input);
    for (std::size_t i = 0; i < controllers.size(); ++i) {
      const ControllerEvaluation& e = planner.evaluations()[i];
      ControllerScore& s = plan.controllers[i];
      if (e.admissible) {
        score_sum[i] += e.score - e.switch_cost;
        ++admissible_cycles[i];
      } else {
        ++s.cycles_ruled_out;
        if (s.ruled_out_reason.empty()) {
          std::ostringstream at;
          at << "at t = " << t << " s, " << planner.RuleOutReason(static_cast<int>(i));
          s.ruled_out_reason = at.str();
        }
      }
    }
    if (chosen < 0) {
      std::ostringstream reason;
      reason << "no admissible controller at t = " << t << " s (body x = " << input.body_xy_W.x() << " m):";
      for (std::size_t i = 0; i < controllers.size(); ++i) {
        reason << (i == 0 ? " " : "; ") << ControllerName(controllers[i]) << ": " << planner.RuleOutReason(static_cast<int>(i));
      }
      failure = reason.str();
      break;
    }
    ++plan.controllers[static_cast<std::size_t>(chosen)].cycles_selected;
    // Commit the first phase of the chosen plan (one leg for a crawl, a pair for a trot).
    const ControllerEvaluation& e = planner.evaluation(chosen);
    const double T = controllers[static_cast<std::size_t>(chosen)].cadence_s;
    for (int k = 0; k < e.step_count; ++k) {
      const PlannedStep& s = e.steps[static_cast<std::size_t>(k)];
      if (s.t_liftoff > t + 1e-9) break;
      Footstep f;
      f.leg = planner.legs()[static_cast<std::size_t>(s.leg)].name;
      f.t_liftoff = s.t_liftoff;
      f.t_touchdown = s.t_touchdown;
      f.position_W = s.target_W;
      f.from_W = s.from_W;
      f.stair_index = s.target_stair;
      f.in_step_region = map.InStepRegion(s.target_stair, s.target_W.head<2>());
      plan.footsteps.push_back(f);
      StepLegState& leg = input.legs[static_cast<std::size_t>(s.leg)];
      leg.foot_W = s.target_W;
      leg.stair = s.target_stair;
      leg.last_touchdown_s = s.t_touchdown;
    }
    t += T;
    arrived = std::all_of(input.legs.begin(), input.legs.end(), [&](const StepLegState& l) { return l.stair == last; });
    if (arrived) break;
  }
  if (!arrived && failure.empty()) failure = "did not reach the last surface within max_cycles";

  // The body the plans assumed: constant speed, height and pitch from the stairs' pitch line.
  const int samples = static_cast<int>(std::ceil(t / settings.sample_period - 1e-9));
  for (int k = 0; k <= samples; ++k) {
    const double tk = std::min(t, k * settings.sample_period);
    const Eigen::Vector2d xy = body0 + velocity * tk;
    const Eigen::Isometry3d pose = planner.BodyPoseAt(xy);
    BodyState b;
    b.t = tk;
    b.x = xy.x();
    b.y = xy.y();
    b.z = pose.translation().z();
    b.pitch = planner.BodyPitchAt(xy);
    b.yaw = planner.yaw();
    plan.body.push_back(b);
  }
  finish_scores(plan);
  if (!failure.empty()) return MarkInfeasible(plan, failure);
  return plan;
}

}  // namespace stairplan
