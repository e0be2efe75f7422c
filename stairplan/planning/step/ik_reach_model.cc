#include "stairplan/planning/step/ik_reach_model.h"

#include <cmath>

#include "stairplan/kinematics/body_pose.h"

namespace stairplan {
namespace {

// Base pose as yaw, pitch, roll (R = Rz(yaw) Ry(pitch) Rx(roll), BodyPose's convention).
BodyPose ToBodyPose(const Eigen::Isometry3d& base_W) {
  const Eigen::Matrix3d& r = base_W.linear();
  BodyPose pose;
  pose.position_W = base_W.translation();
  pose.yaw = std::atan2(r(1, 0), r(0, 0));
  pose.pitch = std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0)));
  pose.roll = std::atan2(r(2, 1), r(2, 2));
  return pose;
}

}  // namespace

IkReachModel::IkReachModel(const RobotModel& robot, const IkSettings& settings, double max_fraction)
    : IkReachModel(RobotKinematics(robot), settings, max_fraction) {}

IkReachModel::IkReachModel(const RobotKinematics& kinematics, const IkSettings& settings, double max_fraction)
    : kinematics_(kinematics), settings_(settings), band_(0.0, max_fraction) {
  settings_.Validate();
  workspace_ = std::make_unique<RobotWorkspace>(kinematics_);
}

bool IkReachModel::Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const {
  if (!band_.Reachable(leg, base_W, foot_W)) return false;  // far beyond the chain: no IK needed
  int index = -1;
  for (int i = 0; i < kinematics_.leg_count(); ++i) {
    if (kinematics_.robot().legs()[static_cast<std::size_t>(i)].name == leg.name) index = i;
  }
  if (index < 0) return false;
  return kinematics_.SolveFootIkWorld(index, foot_W, ToBodyPose(base_W), *workspace_, settings_).ok();
}

double IkReachModel::Effort(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const {
  return band_.Effort(leg, base_W, foot_W);
}

}  // namespace stairplan
