// The alignment pose the plan starts from (PCT/US2021/022953 ("Identifying stairs from footfalls")
// [0042], claim 7), for a robot and a flight, in the plan's frame (the Staircase's: x along the
// travel, y to the left with the stairs' centre line at 0, the first riser at x = 0): the body
// centred across the stairs, heading along the travel (turned round when it faces backward), and
// standing where its leading feet, in its standing stance, stand a gap before the end of the first
// surface's step region, the last place the map lets a foot stand before the flight (the gap the
// crawl's start has always left, so that its footholds stay where they were). The standing stance
// has each foot under its hip (the hip's x, the zero pose's foot y: the stance every planner calls
// neutral), the whole stance shifted so that the centre of mass is over the centre of the feet, as
// the quasi-static body path holds it with four feet down. The pipeline starts its crawl here when
// asked (PipelineOptions::start_at_alignment).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace stairplan {

/// The alignment pose and the stance a plan starts in, in the plan's frame.
struct AlignmentStance {
  bool found = false;  ///< false when the robot cannot stand before the flight (see reason)
  std::string reason;  ///< why not, empty when found
  /// The body origin's ground point: centred (y = 0), z the first surface's height [m].
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Facing facing = Facing::kForward;  ///< which way the body faces relative to the travel
  double yaw = 0.0;  ///< the body's heading: 0 facing along the travel, pi facing backward [rad]
  double standoff = 0.0;  ///< from the body origin to the first walking edge met, along the travel [m]
  double riser_distance = 0.0;  ///< from the body origin to the first riser, along the travel [m]
  std::vector<Eigen::Vector3d> feet;  ///< the standing stance's contact points, in the robot's leg order [m]
};

/// The alignment stance for the robot of `kinematics` (the planner's own, not rebuilt here)
/// traversing `stairs` facing `facing` on `map` (the map the plan is made on: its first surface's
/// step region bounds where the feet stand), the hips at `hip_height_fraction` of the legs' reach
/// (BodyPathSettings'), the leading feet `lead_gap` before the step region's end
/// (CrawlSettings::start_gap). Not found when that region is empty or too short for the stance.
AlignmentStance ComputeAlignmentStance(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                                       Facing facing, double hip_height_fraction, double lead_gap);

}  // namespace stairplan
