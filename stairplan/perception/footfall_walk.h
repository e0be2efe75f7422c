// A generator of synthetic footfalls: a quadruped walking a route over flights of stairs placed
// in the world, stepping once per tread with each foot (as a fixed-cadence crawl does), with
// placement scatter and measurement noise. For tests and benchmarks of the footfall detector.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "stairplan/perception/footfall.h"
#include "stairplan/geometry/stair_model.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// A flight in the world, walked along its own +x (its StairSpec's direction says up or down).
struct PlacedFlight {
  Staircase stairs{StairSpec{}};  ///< the flight in its own frame
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();  ///< where the Staircase frame's origin is
  double yaw = 0.0;                                     ///< heading of the Staircase frame's +x

  /// The flight's model in the world (ascending direction, levels, walking edges).
  StairModel Model() const { return ModelOfStaircase(stairs, origin_W, yaw); }
};

/// How WalkFootfalls() steps and how noisy the footfalls are.
struct FootfallWalkSettings {
  double stride = 0.30;          ///< foothold spacing on flat ground [m]
  double half_stance = 0.15;     ///< feet left and right of the path [m]
  double step_period = 0.8;      ///< time between footholds of one foot [s]
  double placement_scatter = 0.02;  ///< uniform +- scatter of each foothold along and across [m]
  double sigma = 0.01;           ///< Gaussian measurement noise per axis [m]
  std::uint32_t seed = 1;  ///< random seed of the scatter and the noise

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// Walks the flights in order, joined by straight walks on flat ground (or on a constant slope
/// when the flights' ends are at different heights). On a flight each foot lands once per tread,
/// in its middle; on landings next to a flight the footholds line up with the treads.
std::vector<Footfall> WalkFootfalls(const std::vector<PlacedFlight>& route, const FootfallWalkSettings& settings = {});

}  // namespace stairplan
