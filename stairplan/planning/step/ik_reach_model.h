// Reach through the kinematics: a foothold is reachable when the leg's position IK (stairplan/kinematics/)
// solves within its joint limits. Each query is an IK solve (microseconds), so this suits offline
// plans (PlanWithStepPlanner) rather than the 20 us per-cycle budget, where the geometric model
// is the default.
#pragma once

#include <memory>

#include "stairplan/kinematics/leg_ik.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/step/reach_model.h"

namespace stairplan {

/// Reach by IK within the joint limits (offline plans; see the file's top comment).
class IkReachModel final : public ReachModel {
 public:
  /// Builds the robot's kinematics (throws std::invalid_argument as RobotKinematics does).
  /// `max_fraction` rejects far targets before any IK, as the geometric model would.
  explicit IkReachModel(const RobotModel& robot, const IkSettings& settings = {}, double max_fraction = 1.0);
  /// The same on kinematics built already (copied: building them is the costly part).
  explicit IkReachModel(const RobotKinematics& kinematics, const IkSettings& settings = {}, double max_fraction = 1.0);

  /// True when the IK puts the foot centre at foot_W within the joint limits. Not thread-safe: one
  /// workspace, reused by every query.
  bool Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const override;
  /// The geometric effort (0 mid-range, 1 at the ends of the reach band).
  double Effort(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const override;

  /// The robot's kinematics the IK runs on.
  const RobotKinematics& kinematics() const { return kinematics_; }

 private:
  RobotKinematics kinematics_;
  IkSettings settings_;
  GeometricReachModel band_;
  std::unique_ptr<RobotWorkspace> workspace_;
};

}  // namespace stairplan
