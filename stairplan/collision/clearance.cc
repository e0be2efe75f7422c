#include "stairplan/collision/clearance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "stairplan/collision/shape_support.h"
#include "stairplan/collision/signed_distance.h"

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

// A shape pair still to measure and the bounding spheres' bound on its distance.
struct PairCandidate {
  double sphere_bound = 0.0;
  int a = 0;
  int b = 0;
};

// The pairs of one query, measured in order of their bounds so that the first measured are the
// likely closest and the rest mostly fall to the bounds. A fixed array keeps the query free of
// allocation; pairs beyond its size are measured as they come, which changes only the cost.
class ClosestFirst {
 public:
  /// False when full: the caller measures (a, b) at once.
  bool Push(double sphere_bound, int a, int b) {
    if (size_ == pairs_.size()) return false;
    pairs_[size_++] = {sphere_bound, a, b};
    return true;
  }
  /// Puts the pairs in increasing order of their bounds (ties in index order).
  void Sort() {
    std::sort(pairs_.begin(), pairs_.begin() + static_cast<std::ptrdiff_t>(size_),
              [](const PairCandidate& x, const PairCandidate& y) {
                return x.sphere_bound < y.sphere_bound ||
                       (x.sphere_bound == y.sphere_bound && (x.a < y.a || (x.a == y.a && x.b < y.b)));
              });
  }
  const PairCandidate* begin() const { return pairs_.data(); }
  const PairCandidate* end() const { return pairs_.data() + size_; }

 private:
  std::array<PairCandidate, 128> pairs_;
  std::size_t size_ = 0;
};

// Whether a pair measured at `distance` replaces `best`: closer, or as close and earlier in the
// shapes' order (the pair a plain loop over the shapes would have kept).
bool Replaces(double distance, int a, int b, const Clearance& best) {
  return distance < best.distance ||
         (distance == best.distance && (a < best.shape || (a == best.shape && b < best.other)));
}

// Measures robot shape `index` at `pose_W` against stair solid `s` and folds it into `best`,
// unless its support bound already says it cannot beat `best` or the pruning bound.
void ShapeAgainstSolid(const CollisionShape& shape, const Eigen::Isometry3d& pose_W, const StairCollisionModel& stairs,
                       std::size_t s, const ClearanceOptions& options, int leg, int index, Clearance& best) {
  const StairSolid& solid = stairs.solids()[s];
  const double threshold = std::min(best.distance, options.prune_above);
  if (BoxSeparationLowerBound(*shape.geometry, pose_W, shape.bounding_radius, solid.box) >= threshold) return;
  SignedDistanceHints hints;
  hints.bounding_radius_a = shape.bounding_radius;
  hints.box_b = &solid.box;
  const SignedDistanceResult r = SignedDistance(*shape.geometry, pose_W, *solid.geometry, solid.pose, hints);
  if (Replaces(r.distance, index, static_cast<int>(s), best)) {
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

// The clearance of `shapes` (posed by pose_of, the solids of shape i's support plane skipped as
// support_z_of(i) says) against every stair solid.
template <typename PoseOf, typename SupportZOf>
Clearance ShapesAgainstStairs(const std::vector<CollisionShape>& shapes, const PoseOf& pose_of,
                              const SupportZOf& support_z_of, const StairCollisionModel& stairs,
                              const ClearanceOptions& options, int leg) {
  Clearance best;
  ClosestFirst queue;
  const auto& solids = stairs.solids();
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const CollisionShape& shape = shapes[i];
    if (options.skip_foot_contact && shape.foot_contact) continue;
    const Eigen::Isometry3d pose_W = pose_of(shape);
    const double support_z = support_z_of(shape, pose_W);
    for (std::size_t s = 0; s < solids.size(); ++s) {
      const StairSolid& solid = solids[s];
      if (std::abs(support_z - solid.box.max.z()) <= options.support_tolerance) continue;
      const double lower_bound = solid.box.SignedDistance(pose_W.translation()) - shape.bounding_radius;
      if (lower_bound >= options.prune_above) continue;
      if (!queue.Push(lower_bound, static_cast<int>(i), static_cast<int>(s))) {
        ShapeAgainstSolid(shape, pose_W, stairs, s, options, leg, static_cast<int>(i), best);
      }
    }
  }
  queue.Sort();
  for (const PairCandidate& pair : queue) {
    if (pair.sphere_bound >= std::min(best.distance, options.prune_above)) break;
    const CollisionShape& shape = shapes[static_cast<std::size_t>(pair.a)];
    ShapeAgainstSolid(shape, pose_of(shape), stairs, static_cast<std::size_t>(pair.b), options, leg, pair.a, best);
  }
  return best;
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
  const auto support_z_of = [&](const CollisionShape& shape, const Eigen::Isometry3d& pose_W) {
    return IgnorableSupportZ(shape, pose_W, foot_contact_z);
  };
  return ShapesAgainstStairs(shapes, pose_of, support_z_of, stairs, options, leg);
}

Clearance BodyStairClearance(const RobotCollisionModel& robot, const StairCollisionModel& stairs, const BodyPose& body,
                             const ClearanceOptions& options) {
  const Eigen::Isometry3d body_W = body.ToIsometry();
  const auto pose_of = [&](const CollisionShape& shape) -> Eigen::Isometry3d { return body_W * shape.local; };
  const auto no_support = [](const CollisionShape&, const Eigen::Isometry3d&) {
    return std::numeric_limits<double>::quiet_NaN();
  };
  return ShapesAgainstStairs(robot.body_shapes(), pose_of, no_support, stairs, options, -1);
}

Clearance LegLegClearance(const RobotKinematics& kinematics, const RobotCollisionModel& robot, int leg_a,
                          const Eigen::Vector3d& q_a, int leg_b, const Eigen::Vector3d& q_b, RobotWorkspace& ws,
                          double prune_above) {
  const std::vector<Eigen::Isometry3d>& frames_a = kinematics.leg(leg_a).LinkFrames(q_a, ws.leg(leg_a));
  const std::vector<Eigen::Isometry3d>& frames_b = kinematics.leg(leg_b).LinkFrames(q_b, ws.leg(leg_b));
  const auto& shapes_a = robot.leg_shapes(leg_a);
  const auto& shapes_b = robot.leg_shapes(leg_b);
  const auto pose_a = [&](int i) -> Eigen::Isometry3d {
    const CollisionShape& shape = shapes_a[static_cast<std::size_t>(i)];
    return frames_a[static_cast<std::size_t>(shape.segment)] * shape.local;
  };
  const auto pose_b = [&](int j) -> Eigen::Isometry3d {
    const CollisionShape& shape = shapes_b[static_cast<std::size_t>(j)];
    return frames_b[static_cast<std::size_t>(shape.segment)] * shape.local;
  };
  Clearance best;
  const auto measure = [&](int i, int j) {
    const CollisionShape& a = shapes_a[static_cast<std::size_t>(i)];
    const CollisionShape& b = shapes_b[static_cast<std::size_t>(j)];
    const Eigen::Isometry3d pa = pose_a(i), pb = pose_b(j);
    const double threshold = std::min(best.distance, prune_above);
    if (SeparationLowerBound(*a.geometry, pa, a.bounding_radius, *b.geometry, pb, b.bounding_radius) >= threshold) return;
    SignedDistanceHints hints;
    hints.bounding_radius_a = a.bounding_radius;
    hints.bounding_radius_b = b.bounding_radius;
    const SignedDistanceResult r = SignedDistance(*a.geometry, pa, *b.geometry, pb, hints);
    if (Replaces(r.distance, i, j, best)) {
      best.distance = r.distance;
      best.point_robot_W = r.point_a;
      best.point_other_W = r.point_b;
      best.leg = leg_a;
      best.shape = i;
      best.other = j;
    }
    best.fallback = best.fallback || r.fallback;
  };
  ClosestFirst queue;
  for (int i = 0; i < static_cast<int>(shapes_a.size()); ++i) {
    const Eigen::Isometry3d pa = pose_a(i);
    for (int j = 0; j < static_cast<int>(shapes_b.size()); ++j) {
      const double lower_bound = (pa.translation() - pose_b(j).translation()).norm() -
                                 shapes_a[static_cast<std::size_t>(i)].bounding_radius -
                                 shapes_b[static_cast<std::size_t>(j)].bounding_radius;
      if (lower_bound >= prune_above) continue;
      if (!queue.Push(lower_bound, i, j)) measure(i, j);
    }
  }
  queue.Sort();
  for (const PairCandidate& pair : queue) {
    if (pair.sphere_bound >= std::min(best.distance, prune_above)) break;
    measure(pair.a, pair.b);
  }
  return best;
}

}  // namespace stairplan
