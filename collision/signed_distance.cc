#include "collision/signed_distance.h"

#include <cmath>
#include <exception>
#include <limits>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

namespace stairplan {
namespace {

// Lower bound of the signed distance from bounding volumes, used when FCL fails.
SignedDistanceResult Fallback(const Eigen::Isometry3d& pose_a, const Eigen::Isometry3d& pose_b,
                              const SignedDistanceHints& hints) {
  SignedDistanceResult r;
  r.fallback = true;
  const Eigen::Vector3d ca = pose_a.translation();
  if (hints.box_b) {
    // Signed distance is 1-Lipschitz: no point of a is deeper than a's centre plus its radius.
    r.distance = hints.box_b->SignedDistance(ca) - hints.bounding_radius_a;
    r.point_b = ca.cwiseMax(hints.box_b->min).cwiseMin(hints.box_b->max);
  } else {
    r.distance = (ca - pose_b.translation()).norm() - hints.bounding_radius_a - hints.bounding_radius_b;
    r.point_b = pose_b.translation();
  }
  r.point_a = ca;
  return r;
}

// Half-extent of a primitive along unit direction n, or -1 for a geometry we do not model.
double Support(const fcl::CollisionGeometryd& g, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& n) {
  switch (g.getNodeType()) {
    case fcl::GEOM_BOX: {
      const Eigen::Vector3d half = 0.5 * static_cast<const fcl::Boxd&>(g).side;
      return (rotation.transpose() * n).cwiseAbs().dot(half);
    }
    case fcl::GEOM_CYLINDER: {
      const auto& c = static_cast<const fcl::Cylinderd&>(g);
      const double along = std::abs(rotation.col(2).dot(n));
      return c.radius * std::sqrt(std::max(0.0, 1.0 - along * along)) + 0.5 * c.lz * along;
    }
    case fcl::GEOM_SPHERE:
      return static_cast<const fcl::Sphered&>(g).radius;
    default:
      return -1.0;
  }
}

// Penetration depth of a into an axis-aligned box by separating axes: the box's three axes and
// a's own (box faces, cylinder axis). Moving a along the best axis by that much separates them,
// so this bounds the true depth from above and equals it for face contacts, which is how legs
// meet stairs. FCL's EPA on a cylinder can pick a far worse direction (a shank in a nosing lip
// reported 8.5 cm deep instead of 1 cm).
double SeparatingAxisDepth(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, const Box3& box,
                           Eigen::Vector3d* axis) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d box_center = box.Center(), box_half = 0.5 * box.Size();
  const auto consider = [&](const Eigen::Vector3d& n) {
    const double s = Support(a, pose_a.linear(), n);
    if (s < 0.0) return;
    const double c = pose_a.translation().dot(n), b = box_center.dot(n), h = n.cwiseAbs().dot(box_half);
    // Push a towards +n (its low end past the box's high end) or towards -n.
    const double up = (b + h) - (c - s), down = (c + s) - (b - h);
    if (up < best) {
      best = up;
      *axis = n;
    }
    if (down < best) {
      best = down;
      *axis = -n;
    }
  };
  for (int i = 0; i < 3; ++i) consider(Eigen::Vector3d::Unit(i));
  for (int i = 0; i < 3; ++i) consider(pose_a.linear().col(i));
  return best;
}

}  // namespace

SignedDistanceResult SignedDistance(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a,
                                    const fcl::CollisionGeometryd& b, const Eigen::Isometry3d& pose_b,
                                    const SignedDistanceHints& hints) {
  SignedDistanceResult r;
  try {
    fcl::DistanceRequestd request;
    request.enable_nearest_points = true;
    request.gjk_solver_type = fcl::GST_INDEP;  // libccd's GJK is wrong on some box pairs (fcl#508)
    request.distance_tolerance = 1e-10;
    fcl::DistanceResultd result;
    const double d = fcl::distance(&a, pose_a, &b, pose_b, request, result);
    if (std::isfinite(d) && d > 0.0) {
      r.distance = d;
      r.point_a = result.nearest_points[0];
      r.point_b = result.nearest_points[1];
      return r;
    }
    // Touching or penetrating. Cylinders against stair boxes: FCL's EPA is unreliable there, the
    // separating axes are exact for face contacts (and never call into EPA, which may throw).
    if (hints.box_b && a.getNodeType() == fcl::GEOM_CYLINDER) {
      Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
      const double depth = std::max(0.0, SeparatingAxisDepth(a, pose_a, *hints.box_b, &axis));
      if (std::isfinite(depth)) {
        // The deepest point of a along -axis, and where it must get to on the box's face.
        r.distance = -depth;
        r.point_a = pose_a.translation() - Support(a, pose_a.linear(), axis) * axis;
        r.point_b = r.point_a + depth * axis;
        return r;
      }
    }
    // Otherwise the depth comes from FCL's contact computation (exact for box-box, sphere-box).
    fcl::CollisionRequestd collision_request(1, true);
    collision_request.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd collision_result;
    fcl::collide(&a, pose_a, &b, pose_b, collision_request, collision_result);
    if (!collision_result.isCollision()) {
      r.distance = 0.0;
      r.point_a = result.nearest_points[0];
      r.point_b = result.nearest_points[1];
      return r;
    }
    const fcl::Contactd& contact = collision_result.getContact(0);
    if (!std::isfinite(contact.penetration_depth) || !contact.normal.allFinite() || !contact.pos.allFinite() ||
        contact.penetration_depth < 0.0) {
      return Fallback(pose_a, pose_b, hints);
    }
    r.distance = -contact.penetration_depth;
    // FCL's normal points from a to b; the deepest points lie half a depth either side of pos.
    r.point_a = contact.pos + 0.5 * contact.penetration_depth * contact.normal;
    r.point_b = contact.pos - 0.5 * contact.penetration_depth * contact.normal;
    return r;
  } catch (const std::exception&) {
    return Fallback(pose_a, pose_b, hints);
  }
}

}  // namespace stairplan
