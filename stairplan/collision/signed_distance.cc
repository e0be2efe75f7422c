#include "stairplan/collision/signed_distance.h"

#include <cmath>
#include <exception>
#include <limits>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "stairplan/collision/shape_support.h"

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

// The point of a furthest along unit direction n (for the deepest point of a penetration).
Eigen::Vector3d SupportPoint(const fcl::CollisionGeometryd& g, const Eigen::Isometry3d& pose, const Eigen::Vector3d& n) {
  const Eigen::Matrix3d& rotation = pose.linear();
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  const Eigen::Vector3d n_local = rotation.transpose() * n;
  if (g.getNodeType() == fcl::GEOM_BOX) {
    const Eigen::Vector3d half = 0.5 * static_cast<const fcl::Boxd&>(g).side;
    for (int i = 0; i < 3; ++i) local[i] = n_local[i] >= 0.0 ? half[i] : -half[i];
  } else if (g.getNodeType() == fcl::GEOM_CYLINDER) {
    const auto& c = static_cast<const fcl::Cylinderd&>(g);
    const Eigen::Vector2d radial = n_local.head<2>();
    if (radial.norm() > 1e-12) local.head<2>() = c.radius * radial.normalized();
    local.z() = n_local.z() >= 0.0 ? 0.5 * c.lz : -0.5 * c.lz;
  } else if (g.getNodeType() == fcl::GEOM_SPHERE) {
    local = static_cast<const fcl::Sphered&>(g).radius * n_local;
  } else if (const Eigen::Vector3d* vertex = MeshSupportVertex(g, n_local)) {
    local = *vertex;
  }
  return pose * local;
}

// Penetration depth of a into an axis-aligned box by separating axes: the box's three axes, a's
// own (box faces, cylinder axis), for a box the nine edge-edge cross products, for a sphere the
// direction from the box's nearest point. Moving a along the best axis by that much separates
// them, so this bounds the true depth from above, and for boxes and spheres it is exact (their
// minimum translation lies along one of those axes). FCL's EPA on a cylinder can pick a far worse
// direction (a shank in a nosing lip reported 8.5 cm deep instead of 1 cm), and FCL's contact
// computation fills a std::vector, which the control loop cannot afford.
double SeparatingAxisDepth(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, const Box3& box,
                           Eigen::Vector3d* axis) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d box_center = box.Center(), box_half = 0.5 * box.Size();
  const auto consider = [&](const Eigen::Vector3d& n) {
    const double s_hi = SupportAlong(a, pose_a.linear(), n), s_lo = SupportAlong(a, pose_a.linear(), -n);
    if (std::isnan(s_hi) || std::isnan(s_lo)) return;
    const double c = pose_a.translation().dot(n), b = box_center.dot(n), h = n.cwiseAbs().dot(box_half);
    // Push a towards +n (its low end past the box's high end) or towards -n.
    const double up = (b + h) - (c - s_lo), down = (c + s_hi) - (b - h);
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
  if (a.getNodeType() == fcl::GEOM_SPHERE || IsMeshGeometry(a)) {
    // Its centre outside the box (near an edge or corner): the axis from the box's nearest point.
    const Eigen::Vector3d c = pose_a.translation(), out = c - c.cwiseMax(box.min).cwiseMin(box.max);
    if (out.norm() > 1e-12) consider(out.normalized());
    if (a.getNodeType() == fcl::GEOM_SPHERE) return best;
  }
  for (int i = 0; i < 3; ++i) consider(pose_a.linear().col(i));
  if (a.getNodeType() != fcl::GEOM_BOX) return best;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d n = Eigen::Vector3d::Unit(i).cross(pose_a.linear().col(j));
      if (n.norm() > 1e-6) consider(n.normalized());  // parallel edges add no axis
    }
  }
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
    // Touching or penetrating a stair box: the separating axes (exact for face contacts and for
    // box-box, no allocation, never into EPA, which may throw).
    const fcl::NODE_TYPE type = a.getNodeType();
    if (hints.box_b && (type == fcl::GEOM_CYLINDER || type == fcl::GEOM_BOX || type == fcl::GEOM_SPHERE || IsMeshGeometry(a))) {
      Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
      const double depth = std::max(0.0, SeparatingAxisDepth(a, pose_a, *hints.box_b, &axis));
      if (std::isfinite(depth)) {
        // The deepest point of a along -axis, and where it must get to on the box's face.
        r.distance = -depth;
        r.point_a = SupportPoint(a, pose_a, -axis);
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
