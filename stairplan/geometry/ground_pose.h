// A robot's pose on the ground as odometry or a footfall log tracks it: where it stands and which
// way its body heads. What stair mode is judged on (stairplan/geometry/stair_mode_engagement.h).
#pragma once

#include <Eigen/Core>

namespace stairplan {

/// A tracked pose on the ground: position and heading, at a time.
struct GroundPose {
  double t = 0.0;  ///< when the robot was there [s]
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< the body's position [m]
  double yaw = 0.0;  ///< the body's heading about z [rad]
};

}  // namespace stairplan
