// PlanExecutor's responses to impacts (seed 000 [0053]-[0068]): RespondToImpact's decision carried
// out on the swing (re-lift, touch down at once, knee forward, adjusted step), and every event
// recorded in the outcome and told to the impact listener.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "stairplan/simulation/executor_leg_state.h"

namespace stairplan {

void PlanExecutor::Reswing(LegState& leg, double tp, const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W,
                           double apex_z) {
  leg.swing = std::make_unique<SwingTrajectory>(from_W, to_W, apex_z, settings_.swing);
  leg.swing_apex = apex_z;
  leg.swing_target_W = to_W;
  leg.swing_t1 = std::max(leg.swing_t1, tp + settings_.impact.min_reswing_time);
  leg.swing_t0 = tp;
}

bool PlanExecutor::Respond(std::size_t i, ImpactKind kind, double tp, const std::string& link, double force) {
  LegState& leg = legs_[i];
  // One answer per impact: a foot pressed on an obstacle is the same impact until the response
  // has had time to act.
  constexpr double kRefractory = 0.1;
  constexpr int kMaxResponses = 3;
  if (tp - leg.t_recorded < kRefractory || tp - leg.t_responded < kRefractory) return false;
  leg.t_recorded = tp;
  const BodyPose body = MeasuredPose();
  ImpactEvent event;
  event.kind = kind;
  event.leg = leg.name;
  event.swing_phase = std::clamp(SwingPhase(leg, tp), 0.0, 1.0);
  event.body_yaw = body.yaw;
  event.target_W = leg.swing_target_W;
  // The stair the plan meant (the map is of the stairs as they are: its stair under the planned
  // point may be the next one when they moved).
  event.target_stair = leg.step >= 0 ? plan_.footsteps[static_cast<std::size_t>(leg.step)].stair_index
                                     : map_.StairAt(event.target_W.head<2>());
  event.swing_foot_W = FootContactPoint(leg);
  for (const LegState& other : legs_) {
    if (other.name[1] == leg.name[1] && other.name[0] != leg.name[0]) event.contralateral_foot_W = FootContactPoint(other);
  }
  const ImpactResponse response = RespondToImpact(event, map_, settings_.impact.response);
  ImpactRecord record;
  record.t = tp;
  record.t_contact = leg.t_first_contact;
  record.leg = leg.name;
  record.kind = kind;
  record.source = settings_.impact.source;
  record.response = response.kind;
  record.link = link;
  record.swing_phase = event.swing_phase;
  record.force_n = force;
  record.reason = response.reason;
  record.at_W = event.swing_foot_W;
  record.target_W = leg.swing_target_W;
  if (!settings_.impact.respond || leg.responses >= kMaxResponses || response.kind == ResponseKind::kProceed ||
      response.kind == ResponseKind::kClassifyStance) {
    RecordImpact(record);
    return false;
  }
  leg.t_responded = tp;
  ++leg.responses;
  const Eigen::Vector3d foot = event.swing_foot_W;
  Eigen::Vector3d back = leg.swing_target_W - foot;
  back.z() = 0.0;
  back = back.norm() > 1e-9 ? Eigen::Vector3d(-back.normalized()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d retracted = foot + settings_.impact.retract_distance * back;
  switch (response.kind) {
    case ResponseKind::kElevateFoot:  // draw back, lift higher than what stopped it, go on to the target
      Reswing(leg, tp, retracted, leg.swing_target_W, std::max(leg.swing_apex, foot.z()) + response.extra_swing_height);
      break;
    case ResponseKind::kTouchdownNow: {  // go down where the foot is, clear of what it hit
      Eigen::Vector3d down = retracted;
      down.z() = response.target_W.z();  // the tread under the foot in the map
      Reswing(leg, tp, retracted, down, retracted.z());
      leg.swing_t1 = tp + 0.5 * settings_.impact.min_reswing_time;
      break;
    }
    case ResponseKind::kMoveKneeForward: {
      const Eigen::Vector3d forward(std::cos(body.yaw), std::sin(body.yaw), 0.0);
      Reswing(leg, tp, foot + response.knee_forward * forward, leg.swing_target_W, leg.swing_apex);
      break;
    }
    case ResponseKind::kAdjustStep:
      if (kind == ImpactKind::kMisplacedTouchdown) {  // a short hop from where it came down
        Reswing(leg, tp, foot, response.target_W, std::max(foot.z(), response.target_W.z()) + settings_.swing.min_lift);
        leg.swing_t1 = tp + settings_.impact.hop_time;
        break;
      }
      [[fallthrough]];
    case ResponseKind::kAdjustStepRisky:
    case ResponseKind::kUntangle: {
      const Eigen::Vector3d from = response.waypoints_W.empty() ? foot : response.waypoints_W.front();
      Reswing(leg, tp, from, response.target_W, std::max(leg.swing_apex, response.target_W.z() + settings_.swing.min_lift));
      break;
    }
    default:
      break;
  }
  record.executed = true;
  record.target_W = leg.swing_target_W;
  RecordImpact(record);
  return true;
}

void PlanExecutor::RecordImpact(const ImpactRecord& record) {
  outcome_.impacts.push_back(record);
  if (impact_listener_) impact_listener_(outcome_.impacts.back());
}

}  // namespace stairplan
