#include "planning/stair_approach.h"

#include <cmath>

#include "geometry/stair_model.h"

namespace stairplan {

StairApproach ApproachStairs(const Staircase& stairs, const AlignmentStance& alignment, const std::optional<GroundPose>& robot,
                             const StairModeSettings& settings) {
  StairApproach a;
  a.alignment = alignment;
  a.robot_known = robot.has_value();
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

StartOffset PlanStartOffset(const Plan& plan, const AlignmentStance& alignment) {
  if (plan.body.empty()) return {};
  const BodyState& b = plan.body.front();
  return {std::hypot(b.x - alignment.position.x(), b.y - alignment.position.y()), std::remainder(b.yaw - alignment.yaw, 2.0 * M_PI)};
}

}  // namespace stairplan
