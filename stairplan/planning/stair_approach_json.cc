#include "stairplan/planning/stair_approach_json.h"

#include <algorithm>
#include <string>

#include "stairplan/geometry/stair_mode.h"

namespace stairplan {
namespace {

nlohmann::json PoseJson(const GroundPose& pose) { return {{"x", pose.xy.x()}, {"y", pose.xy.y()}, {"yaw_rad", pose.yaw}}; }

}  // namespace

nlohmann::json StairApproachToJson(const StairApproach& approach, const Plan& plan, const StairFrame* world) {
  const StairModeEngagement& mode = approach.stair_mode;
  nlohmann::json robot = PoseJson(mode.pose);
  robot["source"] = ToString(approach.robot_source);
  if (approach.robot_source == RobotPoseSource::kFootfallTrack) robot["t_s"] = mode.pose.t;
  if (world) robot["world"] = PoseJson(world->ToWorld(mode.pose));
  nlohmann::json stair_mode = {{"engaged", mode.engaged},
                               {"distance_m", mode.distance},
                               {"engage_distance_m", mode.engage_distance},
                               {"robot", robot}};
  const AlignmentStance& a = approach.alignment;
  nlohmann::json alignment = {{"found", a.found}};
  if (!a.found) {
    alignment["reason"] = a.reason;
    return {{"stair_mode", stair_mode}, {"alignment", alignment}};
  }
  nlohmann::json feet = nlohmann::json::array();
  for (std::size_t i = 0; i < a.feet.size(); ++i) {
    feet.push_back({{"leg", i < plan.legs.size() ? plan.legs[i] : std::to_string(i)}, {"x", a.feet[i].x()}, {"y", a.feet[i].y()}, {"z", a.feet[i].z()}});
  }
  const StartOffset offset = PlanStartOffset(plan, a);
  alignment.update({{"x", a.position.x()},
                    {"y", a.position.y()},
                    {"z", a.position.z()},
                    {"yaw_rad", a.yaw},
                    {"standoff_m", a.standoff},
                    {"riser_distance_m", a.riser_distance},
                    {"feet", feet},
                    {"move_m", {approach.move.x(), approach.move.y()}},
                    {"turn_rad", approach.turn},
                    {"plan_start_offset_m", offset.distance},
                    {"plan_start_yaw_offset_rad", offset.yaw}});
  if (world) {
    // The patent's pose for the stairs in the world, at the standoff the robot's stance needs.
    const AlignmentPose pose = ComputeAlignmentPose(world->model, world->travel, a.facing, std::max(0.0, a.standoff));
    alignment["world"] = {{"x", pose.position.x()},
                          {"y", pose.position.y()},
                          {"z", pose.position.z()},
                          {"yaw_rad", pose.yaw},
                          {"sensor_direction", {pose.sensor_direction.x(), pose.sensor_direction.y(), pose.sensor_direction.z()}}};
  }
  return {{"stair_mode", stair_mode}, {"alignment", alignment}};
}

}  // namespace stairplan
