// Robot- and direction-aware collision regions: for every stair surface, footholds are sampled
// along the tread with the robot in its stair posture (body pitched along the flight, the leg's
// hip straight above the foot at the planner's hip height); where the leg that puts its foot there
// would touch the riser or the nosing, that stretch of the tread becomes a kRobot collision region
// of the ConstrainedMap, which trims its step region. The analytic margins stay as they were.
#pragma once

#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/collision/stair_collision_model.h"
#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace stairplan {

/// How FindRobotCollisionRegions() samples the footholds.
struct RobotRegionSettings {
  double sample_step = 0.01;          ///< foothold spacing along each surface [m]
  double min_clearance = 0.0;         ///< a foothold needs more clearance than this [m]
  double hip_height_fraction = 0.75;  ///< hip above the foot's sphere, as a fraction of LegModel::max_reach
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// One stretch of a surface found unsafe.
struct RobotRegion {
  int stair_index = 0;  ///< the surface (Staircase::surface index)
  ///@{
  double x0 = 0.0, x1 = 0.0;       ///< along travel [m]
  ///@}
  StairPart part = StairPart::kOther;  ///< what the leg would hit
  int leg = -1;                    ///< the first leg found hitting it
};

/// Samples every surface of `stairs` for every leg (feet at their nominal lateral offset; the
/// body faces map.facing()) and returns the unsafe stretches, merged per surface. Footholds the
/// leg cannot reach in that posture are not regions (another body pose may reach them).
std::vector<RobotRegion> FindRobotCollisionRegions(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                                                   const Staircase& stairs, Facing facing,
                                                   const RobotRegionSettings& settings = {});

/// Adds FindRobotCollisionRegions() to `map` as kRobot bands (trimming its step regions).
void AddRobotCollisionRegions(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                              const Staircase& stairs, ConstrainedMap& map, const RobotRegionSettings& settings = {});

}  // namespace stairplan
