// The robot's track through a footfall log (PCT/US2021/022953 ("Identifying stairs from
// footfalls") [0044]-[0046]: each footfall carries the robot's odometry): after each footfall the
// body stands over the centre of every leg's latest footfall, heading from the hind feet to the
// front ones. Replayed through stair mode it says where the robot was when the mode engaged.
#pragma once

#include <vector>

#include "stairplan/perception/footfall.h"
#include "stairplan/geometry/ground_pose.h"

namespace stairplan {

/// The body's pose after each footfall (in time order) from the moment every leg of the log has
/// touched down once: the centre of every leg's latest footfall, headed from the hind feet's
/// centre to the front feet's. Legs named side and end (LF, RF, LH, RH, or FL, FR, HL, HR) give
/// the heading; a log whose legs are not named so is headed along its path (from the previous
/// pose; the first pose takes the second's heading). Empty for an empty log.
std::vector<GroundPose> TrackFromFootfalls(const std::vector<Footfall>& footfalls);

}  // namespace stairplan
