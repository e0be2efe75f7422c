// The pose of the robot's base in the world, as planners describe it: position, pitch and yaw
// (roll rarely matters on stairs but is kept for completeness).
#pragma once

#include <Eigen/Geometry>

namespace stairplan {

/// Base frame pose in the world. Rotation = Rz(yaw) * Ry(pitch) * Rx(roll); pitch follows the
/// right-hand rule about the body's y axis, so nose-up is negative (as in stairplan/planning/plan.h).
struct BodyPose {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  ///< base link origin [m]
  double roll = 0.0;   ///< [rad]
  double pitch = 0.0;  ///< [rad]
  double yaw = 0.0;    ///< [rad]

  /// The transform from base to world.
  Eigen::Isometry3d ToIsometry() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    t.translation() = position_W;
    return t;
  }
};

}  // namespace stairplan
