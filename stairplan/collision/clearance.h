// Clearances between the robot and the stairs, and between contralateral legs: the smallest
// signed distance over all shape pairs with the closest points, in the world frame. Pairs are
// measured closest first by their bounding spheres, and a pair whose lower bound (bounding spheres,
// then the shapes' extents along the line between them) cannot beat the closest measured is
// skipped, so a leg far from the stairs costs a few box distances. No allocation of ours for
// separated configurations (FCL's support search on a hull allocates).
#pragma once

#include <limits>

#include <Eigen/Core>

#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/collision/stair_collision_model.h"
#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace stairplan {

/// The closest pair found.
struct Clearance {
  double distance = std::numeric_limits<double>::infinity();  ///< signed, negative inside [m]
  Eigen::Vector3d point_robot_W = Eigen::Vector3d::Zero();  ///< on the robot shape (leg a for leg pairs)
  Eigen::Vector3d point_other_W = Eigen::Vector3d::Zero();  ///< on the stair solid (or leg b)
  int leg = -1;     ///< the robot shape's leg (-1: body)
  int shape = -1;   ///< index into leg_shapes(leg) or body_shapes()
  int other = -1;   ///< stair solid index, or shape index on leg b
  StairPart part = StairPart::kOther;  ///< for stairs: what was closest
  bool fallback = false;  ///< FCL failed on some pair; distance is a conservative bound
};

/// Options of the robot-versus-stairs queries.
struct ClearanceOptions {
  /// The foot's contact sphere touches the surface it stands on by design: skip the solids whose
  /// top is within support_tolerance of the sphere's bottom (that surface and the nosing lip in
  /// its plane) for the sphere and for the foot's other parts (CollisionShape::foot_part) whose
  /// lowest point is not below the sphere's; they still see the risers and nosings above, the
  /// other treads, and the support itself when they dip below the contact.
  bool skip_foot_support = true;
  double support_tolerance = 2e-3;  ///< [m]
  /// Leaves the foot's contact shape out: a swing foot goes where its swing trajectory takes it,
  /// so a body planner's rows look at the rest of the leg, which the body does move.
  bool skip_foot_contact = false;
  /// Shape pairs that are surely farther apart than this are not measured: a result at or above
  /// it then says only "at least this far". For yes/no checks against a margin (stance checks
  /// probe thousands of poses); infinity (the default) measures the exact clearance.
  double prune_above = std::numeric_limits<double>::infinity();  ///< [m]
};

/// Clearance of leg `leg` at joint angles q, with the body at `body`, to every stair solid.
Clearance LegStairClearance(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                            const StairCollisionModel& stairs, int leg, const Eigen::Vector3d& q, const BodyPose& body,
                            RobotWorkspace& ws, const ClearanceOptions& options = {});

/// Clearance of the body's shapes to every stair solid (options.prune_above applies; the foot
/// support rule does not concern the body).
Clearance BodyStairClearance(const RobotCollisionModel& robot, const StairCollisionModel& stairs, const BodyPose& body,
                             const ClearanceOptions& options = {});

/// Clearance between leg a at q_a and leg b at q_b (e.g. LF and RF, the contralateral pair); points
/// in the base frame (the body pose does not change it). prune_above as in ClearanceOptions.
Clearance LegLegClearance(const RobotKinematics& kinematics, const RobotCollisionModel& robot, int leg_a,
                          const Eigen::Vector3d& q_a, int leg_b, const Eigen::Vector3d& q_b, RobotWorkspace& ws,
                          double prune_above = std::numeric_limits<double>::infinity());

}  // namespace stairplan
