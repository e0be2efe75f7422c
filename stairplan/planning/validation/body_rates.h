// The body's accelerations at any instant of a plan, linear and angular, for the dynamic check:
// second differences at the body samples (as BodyAccelerationAt, plan_timeline.h, takes them for
// the position), interpolated linearly in time between samples, so every judge that reads the
// timeline sees the same motion.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stairplan/planning/plan.h"

namespace stairplan {

/// The body's linear and angular acceleration at one instant, world frame.
struct BodyRates {
  Eigen::Vector3d linear_W = Eigen::Vector3d::Zero();   ///< of the base origin [m/s^2]
  Eigen::Vector3d angular_W = Eigen::Vector3d::Zero();  ///< from pitch and yaw [rad/s^2]
};

/// The accelerations at time t: the samples' second differences, interpolated between samples
/// (zero at the first and last sample and for fewer than three). The angular part is
/// yaw'' z + pitch'' (the body's y axis): the Euler-rate products (yaw' pitch') are left out, as
/// a plan's turns on stairs are slow.
BodyRates BodyRatesAt(const std::vector<BodyState>& body, double t);

}  // namespace stairplan
