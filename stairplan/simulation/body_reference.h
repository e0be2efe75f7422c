// The executor's reference for the body: the plan's body samples joined by a cubic (Catmull-Rom)
// spline, so that the controller has a velocity and an acceleration to feed forward. The plan's
// own linear interpolation has a velocity that jumps at every sample and no acceleration; a
// controller that only sees positions reacts to the body shifts after they have happened.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// The body at one instant of plan time, with its time derivatives (per second of plan time).
struct BodyReferenceState {
  BodyPose pose;  ///< the body's pose
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();      ///< [m/s]
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();  ///< [m/s^2]
  double pitch_rate = 0.0;                                    ///< [rad/s]
  double yaw_rate = 0.0;                                      ///< [rad/s]

  /// The body's angular velocity in world axes [rad/s]: the pitch rate about the yawed body's y
  /// axis and the yaw rate about z.
  Eigen::Vector3d AngularVelocityW() const {
    return pitch_rate * Eigen::Vector3d(-std::sin(pose.yaw), std::cos(pose.yaw), 0.0) + yaw_rate * Eigen::Vector3d::UnitZ();
  }
};

/// The spline through `body` at plan time t (clamped to the plan; at rest before and after). The
/// spline passes through every sample; the body starts and ends at rest.
BodyReferenceState BodyReferenceAt(const std::vector<BodyState>& body, double t);

}  // namespace stairplan
