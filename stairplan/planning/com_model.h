// The robot's centre of mass for given leg joint angles: the base's links lumped at the base
// link's inertial origin, every leg link at its own inertial origin through the leg's FK.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

/// The robot's centre of mass from the body pose and the legs' joint angles (every link's inertial).
class ComModel {
 public:
  /// Collects every link's mass and centre from the URDF of `kinematics`' robot.
  explicit ComModel(const RobotKinematics& kinematics);

  /// The centre of mass in the world for the body pose and the four legs' joint angles.
  Eigen::Vector3d Com(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& q, RobotWorkspace& ws) const;
  /// Sum of every link's mass [kg].
  double total_mass() const { return total_mass_; }

 private:
  struct Part {
    int segment = -1;  // leg chain segment carrying it
    double mass = 0.0;
    Eigen::Vector3d com_local = Eigen::Vector3d::Zero();
  };
  const RobotKinematics& kinematics_;
  std::vector<std::vector<Part>> legs_;
  double base_mass_ = 0.0;
  Eigen::Vector3d base_com_B_ = Eigen::Vector3d::Zero();
  double total_mass_ = 0.0;
};

/// The centre of mass in the base frame at the robot's zero pose, legs lumped at their hips [m].
Eigen::Vector3d ApproximateComOffset(const RobotModel& robot);

}  // namespace stairplan
