// The robot before the flight it plans (PCT/US2021/022953 ("Identifying stairs from footfalls")
// [0042]-[0043], claim 7): stair mode is judged at the robot's tracked pose (on within the engage
// distance of the flight); the robot then orients itself to the alignment pose, where the plan
// starts (PipelineOptions::start_at_alignment). A robot farther away is not in stair mode yet: the
// plan, planned in advance as [0042] allows, says so, and the robot must first come to that pose.
// All in the plan's frame (stairplan/planning/stair_alignment.h).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/ground_pose.h"
#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/stair_mode.h"
#include "stairplan/geometry/stair_mode_engagement.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/stair_alignment.h"

namespace stairplan {

/// Where the robot's pose the stair mode was judged at came from.
enum class RobotPoseSource {
  kAlignment,     ///< none was known: the robot is taken to be at the alignment pose
  kGiven,         ///< given by the caller (`plan --start`, plan()'s start)
  kFootfallTrack, ///< where stair mode engaged along the footfall log's track
};
/// "alignment", "given", "footfall_track".
const char* ToString(RobotPoseSource source);

/// The plan's start against the robot: stair mode at its pose and its move to the alignment pose.
struct StairApproach {
  AlignmentStance alignment;  ///< the alignment pose and its stance
  /// Where the robot's pose came from; kAlignment when none was given (the robot is taken to be
  /// at the alignment pose).
  RobotPoseSource robot_source = RobotPoseSource::kAlignment;
  bool robot_known() const { return robot_source != RobotPoseSource::kAlignment; }  ///< a pose was given
  /// Stair mode at the robot's pose (plan frame); with no pose, at the alignment pose.
  StairModeEngagement stair_mode;
  Eigen::Vector2d move = Eigen::Vector2d::Zero();  ///< from the robot's position to the alignment pose's [m]
  double turn = 0.0;  ///< from the robot's heading to the alignment pose's, in [-pi, pi] [rad]
};

/// Stair mode and the move to `alignment` for a robot at `robot` (plan frame; none: at the
/// alignment pose), which came from `source`. Throws FieldError for bad settings.
StairApproach ApproachStairs(const Staircase& stairs, const AlignmentStance& alignment, const std::optional<GroundPose>& robot,
                             const StairModeSettings& settings = {}, RobotPoseSource source = RobotPoseSource::kGiven);

/// The robot's pose given as {x, y, yaw} [m, m, rad] (`plan --start`), in the plan's frame: given
/// in `world` when the stairs were found there (a cloud, footfalls), else (null) in the plan's
/// frame. Throws std::invalid_argument unless three finite numbers.
GroundPose RobotPoseInPlanFrame(const std::vector<double>& xy_yaw, const StairFrame* world);

/// How far a plan's first body state is from the alignment pose.
struct StartOffset {
  double distance = 0.0;  ///< horizontal [m]
  double yaw = 0.0;  ///< heading, in [-pi, pi] [rad]
};

/// The plan's first body state against the alignment pose; zero for a plan without a body.
StartOffset PlanStartOffset(const Plan& plan, const AlignmentStance& alignment);

}  // namespace stairplan
