#include "collision/clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/signed_distance.h"

namespace stairplan {
namespace {

// A foot part this far below the foot's own contact point would be inside the surface the foot
// rests on: only round-off is forgiven [m].
constexpr double kBelowContactTolerance = 1e-6;

// The height of the surface leg shape `shape` may ignore, or NaN. A foot sphere resting on a
// surface touches every solid whose top lies in that plane (the tread and the nosing lip in front
// of it); from above it cannot enter them, so they are not obstacles. Nor are they for another
// part of the foot (rigid with it) whose lowest point is no lower than the sphere's contact: with
// the foot down on the plane it stays above the plane, outside every solid whose top that plane
// is (ANYmal B's adapter tube ends 7.75 mm above the contact and at any tilt stays 3.3 mm above
// it). Dipping below the contact, it is measured against that surface like any other; risers,
// nosings and other treads always are.
// The foot's contact shape itself always ignores it: a mesh foot rolled off its nominal contact
// point dips a little below it, as a real foot does.
double IgnorableSupportZ(const CollisionShape& shape, const Eigen::Isometry3d& pose_W, double foot_contact_z) {
  if (!shape.foot_part || (!shape.foot_contact && !(LowestZ(shape, pose_W) >= foot_contact_z - kBelowContactTolerance))) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return foot_contact_z;
}

// Where the foot touches what it stands on: a sphere's lowest point, the bottom of a mesh foot's
// contact sphere.
double FootContactZ(const CollisionShape& contact, const Eigen::Isometry3d& pose_W) {
  return contact.type == ShapeType::kMesh ? (pose_W * contact.contact_point).z() - contact.contact_radius
                                          : LowestZ(contact, pose_W);
}

// Folds the clearance of one robot shape against every stair solid into `best`.
// Solids whose top is within options.support_tolerance of support_z (NaN: none) are skipped.
void ShapeAgainstStairs(const CollisionShape& shape, const Eigen::Isometry3d& pose_W, const StairCollisionModel& stairs,
                        const ClearanceOptions& options, double support_z, int leg, int index, Clearance& best) {
  const auto& solids = stairs.solids();
  for (std::size_t s = 0; s < solids.size(); ++s) {
    const StairSolid& solid = solids[s];
    if (std::abs(support_z - solid.box.max.z()) <= options.support_tolerance) continue;
    const double lower_bound = solid.box.SignedDistance(pose_W.translation()) - shape.bounding_radius;
    if (lower_bound >= std::min(best.distance, options.prune_above)) continue;
    SignedDistanceHints hints;
    hints.bounding_radius_a = shape.bounding_radius;
    hints.box_b = &solid.box;
    const SignedDistanceResult r = SignedDistance(*shape.geometry, pose_W, *solid.geometry, solid.pose, hints);
    if (r.distance < best.distance) {
      best.distance = r.distance;
      best.point_robot_W = r.point_a;
      best.point_other_W = r.point_b;
      best.leg = leg;
      best.shape = index;
      best.other = static_cast<int>(s);
      best.part = stairs.PartAt(static_cast<int>(s), r.point_b, 1e-5);
    }
    best.fallback = best.fallback || r.fallback;
  }
}

}  // namespace

Clearance LegStairClearance(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                            const StairCollisionModel& stairs, int leg, const Eigen::Vector3d& q, const BodyPose& body,
                            RobotWorkspace& ws, const ClearanceOptions& options) {
  const Eigen::Isometry3d body_W = body.ToIsometry();
  const std::vector<Eigen::Isometry3d>& frames = kinematics.leg(leg).LinkFrames(q, ws.leg(leg));
  const std::vector<CollisionShape>& shapes = robot.leg_shapes(leg);
  const auto pose_of = [&](const CollisionShape& shape) -> Eigen::Isometry3d {
    return body_W * frames[static_cast<std::size_t>(shape.segment)] * shape.local;
  };
  double foot_contact_z = std::numeric_limits<double>::quiet_NaN();
  const int foot = robot.foot_shape(leg);
  if (options.skip_foot_support && foot >= 0) {
    const CollisionShape& contact = shapes[static_cast<std::size_t>(foot)];
    foot_contact_z = FootContactZ(contact, pose_of(contact));
  }
  Clearance best;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const CollisionShape& shape = shapes[i];
    const Eigen::Isometry3d pose_W = pose_of(shape);
    ShapeAgainstStairs(shape, pose_W, stairs, options, IgnorableSupportZ(shape, pose_W, foot_contact_z), leg,
                       static_cast<int>(i), best);
  }
  return best;
}

Clearance BodyStairClearance(const RobotCollisionModel& robot, const StairCollisionModel& stairs, const BodyPose& body,
                             const ClearanceOptions& options) {
  const Eigen::Isometry3d body_W = body.ToIsometry();
  Clearance best;
  const std::vector<CollisionShape>& shapes = robot.body_shapes();
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    ShapeAgainstStairs(shapes[i], body_W * shapes[i].local, stairs, options, std::numeric_limits<double>::quiet_NaN(), -1,
                       static_cast<int>(i), best);
  }
  return best;
}

Clearance LegLegClearance(const RobotKinematics& kinematics, const RobotCollisionModel& robot, int leg_a,
                          const Eigen::Vector3d& q_a, int leg_b, const Eigen::Vector3d& q_b, RobotWorkspace& ws,
                          double prune_above) {
  const std::vector<Eigen::Isometry3d>& frames_a = kinematics.leg(leg_a).LinkFrames(q_a, ws.leg(leg_a));
  const std::vector<Eigen::Isometry3d>& frames_b = kinematics.leg(leg_b).LinkFrames(q_b, ws.leg(leg_b));
  const auto& shapes_a = robot.leg_shapes(leg_a);
  const auto& shapes_b = robot.leg_shapes(leg_b);
  Clearance best;
  for (std::size_t i = 0; i < shapes_a.size(); ++i) {
    const Eigen::Isometry3d pose_a = frames_a[static_cast<std::size_t>(shapes_a[i].segment)] * shapes_a[i].local;
    for (std::size_t j = 0; j < shapes_b.size(); ++j) {
      const Eigen::Isometry3d pose_b = frames_b[static_cast<std::size_t>(shapes_b[j].segment)] * shapes_b[j].local;
      const double lower_bound = (pose_a.translation() - pose_b.translation()).norm() - shapes_a[i].bounding_radius -
                                 shapes_b[j].bounding_radius;
      if (lower_bound >= std::min(best.distance, prune_above)) continue;
      SignedDistanceHints hints;
      hints.bounding_radius_a = shapes_a[i].bounding_radius;
      hints.bounding_radius_b = shapes_b[j].bounding_radius;
      const SignedDistanceResult r = SignedDistance(*shapes_a[i].geometry, pose_a, *shapes_b[j].geometry, pose_b, hints);
      if (r.distance < best.distance) {
        best.distance = r.distance;
        best.point_robot_W = r.point_a;
        best.point_other_W = r.point_b;
        best.leg = leg_a;
        best.shape = static_cast<int>(i);
        best.other = static_cast<int>(j);
      }
      best.fallback = best.fallback || r.fallback;
    }
  }
  return best;
}

}  // namespace stairplan
