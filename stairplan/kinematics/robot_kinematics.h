// The four legs' kinematics of a RobotModel, built from our URDF-to-KDL tree, and the queries
// that involve the body pose (foot targets in the world, reachable body heights).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <kdl/tree.hpp>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/leg_kinematics.h"
#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

class RobotWorkspace;

/// Const model of the whole robot's leg kinematics. Legs in the RobotModel's order (LF, RF, LH, RH).
class RobotKinematics {
 public:
  /// Builds the KDL tree and the four leg chains. Throws std::invalid_argument naming the leg when
  /// one is not a 3-DoF chain.
  explicit RobotKinematics(const RobotModel& robot);

  /// The robot model it was built from.
  const RobotModel& robot() const { return robot_; }
  /// The KDL tree of the whole robot.
  const KDL::Tree& tree() const { return *tree_; }
  /// Number of legs (four).
  int leg_count() const { return static_cast<int>(legs_.size()); }
  /// Leg `index` (LF, RF, LH, RH order); throws std::out_of_range for a bad index.
  const LegKinematics& leg(int index) const { return legs_.at(static_cast<std::size_t>(index)); }
  /// Throws std::invalid_argument for an unknown name.
  const LegKinematics& leg(const std::string& name) const;
  /// Index of the leg with that name; throws std::invalid_argument for an unknown name.
  int LegIndex(const std::string& name) const;
  /// Every leg, in the RobotModel's order.
  const std::vector<LegKinematics>& legs() const { return legs_; }

  /// IK for leg `index` with the foot link origin at `foot_W` and the body at `body`.
  IkResult SolveFootIkWorld(int index, const Eigen::Vector3d& foot_W, const BodyPose& body, RobotWorkspace& ws,
                            const IkSettings& settings = {}) const;

  /// The contiguous range of body heights (body.position_W.z) around the best one for which leg
  /// `index` reaches `foot_W` within its limits, the rest of `body` fixed. Scans in `step` and
  /// refines both ends by bisection to `tolerance`. Empty when no height works.
  Interval1 ReachableBodyHeights(int index, const Eigen::Vector3d& foot_W, const BodyPose& body, RobotWorkspace& ws,
                                 double step = 0.02, double tolerance = 1e-4) const;

 private:
  RobotModel robot_;
  std::shared_ptr<const KDL::Tree> tree_;
  std::vector<LegKinematics> legs_;
};

/// One thread's scratch space for a RobotKinematics: one LegWorkspace per leg.
class RobotWorkspace {
 public:
  /// One LegWorkspace per leg of `kinematics`, sized once.
  explicit RobotWorkspace(const RobotKinematics& kinematics);
  /// The scratch space of leg `index`; throws std::out_of_range for a bad index.
  LegWorkspace& leg(int index) { return legs_.at(static_cast<std::size_t>(index)); }

 private:
  std::vector<LegWorkspace> legs_;
};

}  // namespace stairplan
