#include "stairplan/planning/stair_approach.h"

#include <cmath>
#include <stdexcept>

#include "stairplan/geometry/stair_model.h"

namespace stairplan {

const char* ToString(RobotPoseSource source) {
  switch (source) {
    case RobotPoseSource::kAlignment: return "alignment";
    case RobotPoseSource::kGiven: return "given";
    case RobotPoseSource::kFootfallTrack: return "footfall_track";
  }
  return "?";
}

StairApproach ApproachStairs(const Staircase& stairs, const AlignmentStance& alignment, const std::optional<GroundPose>& robot,
                             const StairModeSettings& settings, RobotPoseSource source) {
  StairApproach a;
  a.alignment = alignment;
  a.robot_source = robot ? source : RobotPoseSource::kAlignment;
  GroundPose aligned;
  aligned.xy = alignment.position.head<2>();
  aligned.yaw = alignment.yaw;
  const GroundPose at = robot.value_or(aligned);
  // The plan's frame is the staircase's own: the flight placed at its origin, heading +x.
  a.stair_mode = StairModeAtPose(ModelOfStaircase(stairs, Eigen::Vector3d::Zero(), 0.0), at, settings);
  a.move = aligned.xy - at.xy;
  a.turn = std::remainder(aligned.yaw - at.yaw, 2.0 * M_PI);
  return a;
}

GroundPose RobotPoseInPlanFrame(const std::vector<double>& xy_yaw, const StairFrame* world) {
  if (xy_yaw.size() != 3 || !std::isfinite(xy_yaw[0]) || !std::isfinite(xy_yaw[1]) || !std::isfinite(xy_yaw[2])) {
    throw std::invalid_argument("expected three finite numbers X,Y,YAW");
  }
  GroundPose pose;
  pose.xy << xy_yaw[0], xy_yaw[1];
  pose.yaw = xy_yaw[2];
  return world ? world->ToStair(pose) : pose;
}

StartOffset PlanStartOffset(const Plan& plan, const AlignmentStance& alignment) {
  if (plan.body.empty()) return {};
  const BodyState& b = plan.body.front();
  return {std::hypot(b.x - alignment.position.x(), b.y - alignment.position.y()), std::remainder(b.yaw - alignment.yaw, 2.0 * M_PI)};
}

}  // namespace stairplan
