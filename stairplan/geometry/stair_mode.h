// Using a stair model (PCT/US2021/022953 ("Identifying stairs from footfalls") [0042]-[0043],
// claims 6-9): a stair mode that switches on when the robot comes within a set distance of a known
// staircase (and off again, with hysteresis, once it has left), and the pose to take before
// climbing or descending: heading along the stairs' direction vector (turned round when the robot
// goes backwards), centred across the width, sensors pointed along the direction of travel.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/stair_model.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// When StairMode switches on and off.
struct StairModeSettings {
  double engage_distance = 1.0;   ///< stair mode switches on this close to a flight [m]
  double release_distance = 1.5;  ///< and off beyond this (>= engage_distance) [m]

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// Horizontal distance from p to the flight's footprint (from its lowest to its highest edge,
/// across its width); 0 on the flight.
double DistanceToFlight(const StairModel& stairs, const Eigen::Vector2d& p);

/// The stair-mode switch over a set of known staircases (from footfalls or the tracker).
class StairMode {
 public:
  /// Throws FieldError for bad settings.
  explicit StairMode(std::vector<StairModel> stairs, const StairModeSettings& settings = {});

  /// Feeds the robot's position; returns the staircase the mode is engaged for, or -1.
  int Update(const Eigen::Vector2d& robot_xy);
  /// True when the mode is engaged for some staircase.
  bool active() const { return active_ >= 0; }
  /// The staircase the mode is engaged for (index into stairs()), or -1.
  int staircase() const { return active_; }
  /// The known staircases.
  const std::vector<StairModel>& stairs() const { return stairs_; }

 private:
  std::vector<StairModel> stairs_;
  StairModeSettings settings_;
  int active_ = -1;
};

/// Where and how the robot lines up before a flight.
struct AlignmentPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< on the centre line, `standoff` before the first edge [m]
  double yaw = 0.0;                                     ///< body heading [rad]
  Eigen::Vector3d sensor_direction = Eigen::Vector3d::UnitX();  ///< unit, along the travel and the stairs' slope
  TravelDirection travel = TravelDirection::kUp;  ///< up or down the stairs
  Facing facing = Facing::kForward;  ///< forwards, or backwards (e.g. to descend)
};

/// The alignment pose for traversing `stairs` in `travel` facing `facing` (e.g. backwards to
/// descend), standing `standoff` before the first edge met. Throws std::invalid_argument for a
/// model without steps or a negative standoff.
AlignmentPose ComputeAlignmentPose(const StairModel& stairs, TravelDirection travel, Facing facing, double standoff = 0.4);

}  // namespace stairplan
