// Where stair mode engages (PCT/US2021/022953 ("Identifying stairs from footfalls") [0043], claim
// 7): judged at one tracked pose of the robot, or along a whole track (odometry, a footfall log)
// through StairMode over every staircase the robot knows, hysteresis included. The planner asks it
// whether the robot it plans for is in stair mode for the flight it plans.
#pragma once

#include <limits>
#include <vector>

#include "stairplan/geometry/ground_pose.h"
#include "stairplan/geometry/stair_mode.h"
#include "stairplan/geometry/stair_model.h"

namespace stairplan {

/// Whether stair mode is engaged for one staircase, and where the robot was.
struct StairModeEngagement {
  bool engaged = false;  ///< the mode is on for this staircase
  /// Where it engaged; when it did not, the pose judged (a track's nearest pose to the flight).
  GroundPose pose;
  double distance = std::numeric_limits<double>::infinity();  ///< the pose's distance from the flight [m]
  double engage_distance = 0.0;  ///< the threshold it was judged against (StairModeSettings) [m]
};

/// Stair mode for `stairs` with the robot at `pose`: on within settings.engage_distance of the
/// flight's footprint (PCT/US2021/022953 [0043]). Throws FieldError for bad settings.
StairModeEngagement StairModeAtPose(const StairModel& stairs, const GroundPose& pose, const StairModeSettings& settings = {});

/// StairMode over the known `stairs`, fed `track` in order: the first pose at which the mode
/// engaged for stairs[staircase] (while it stays engaged for another flight it cannot: the
/// hysteresis of StairMode); not engaged, at the track's nearest pose, when it never did. Throws
/// std::invalid_argument for a staircase index out of range, FieldError for bad settings.
StairModeEngagement EngagementAlongTrack(const std::vector<GroundPose>& track, const std::vector<StairModel>& stairs,
                                         int staircase, const StairModeSettings& settings = {});

}  // namespace stairplan
