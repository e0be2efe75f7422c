#include "stairplan/collision/shape_support.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

namespace stairplan {
namespace {

// Round-off of the bounds, kept on the safe side: a bound must never exceed the true distance.
constexpr double kBoundSlack = 1e-9;

// The spheres' bound tightened by a gap along some axis when that gap is positive. An overlap
// along the axis bounds the penetration depth only from above, and the depth a query reports may
// be larger (separating axes tried on a cylinder, EPA's approximation): the spheres' bound, the
// one that always pruned, stays in force for pairs that may touch.
double Tightened(double spheres, double along) {
  return along > kBoundSlack ? std::max(spheres, along - kBoundSlack) : spheres;
}

}  // namespace

bool IsMeshGeometry(const fcl::CollisionGeometryd& g) {
  return g.getNodeType() == fcl::GEOM_CONVEX || g.getNodeType() == fcl::BV_OBBRSS;
}

const Eigen::Vector3d* MeshSupportVertex(const fcl::CollisionGeometryd& g, const Eigen::Vector3d& n_local) {
  const Eigen::Vector3d* vertices = nullptr;
  int count = 0;
  if (g.getNodeType() == fcl::GEOM_CONVEX) {
    const auto& convex = static_cast<const fcl::Convexd&>(g);
    vertices = convex.getVertices().data();
    count = static_cast<int>(convex.getVertices().size());
  } else if (g.getNodeType() == fcl::BV_OBBRSS) {
    const auto& model = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(g);
    vertices = model.vertices;
    count = model.num_vertices;
  }
  const Eigen::Vector3d* best = nullptr;
  double best_value = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double value = n_local.dot(vertices[i]);
    if (value > best_value) {
      best_value = value;
      best = &vertices[i];
    }
  }
  return best;
}

double SupportAlong(const fcl::CollisionGeometryd& g, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& n) {
  if (IsMeshGeometry(g)) {
    const Eigen::Vector3d n_local = rotation.transpose() * n;
    const Eigen::Vector3d* vertex = MeshSupportVertex(g, n_local);
    return vertex ? n_local.dot(*vertex) : std::numeric_limits<double>::quiet_NaN();
  }
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
      return std::numeric_limits<double>::quiet_NaN();
  }
}

double SeparationLowerBound(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, double radius_a,
                            const fcl::CollisionGeometryd& b, const Eigen::Isometry3d& pose_b, double radius_b) {
  const Eigen::Vector3d between = pose_b.translation() - pose_a.translation();
  const double gap = between.norm();
  const double spheres = gap - radius_a - radius_b;
  if (!(gap > 1e-12)) return spheres;
  // Projection onto a line is 1-Lipschitz: the extents' gap along it bounds the distance.
  const Eigen::Vector3d n = between / gap;
  const double along = gap - SupportAlong(a, pose_a.linear(), n) - SupportAlong(b, pose_b.linear(), -n);
  return Tightened(spheres, along);
}

double BoxSeparationLowerBound(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, double radius_a,
                               const Box3& box) {
  const Eigen::Vector3d c = pose_a.translation();
  const double spheres = box.SignedDistance(c) - radius_a;
  const Eigen::Vector3d out = c - c.cwiseMax(box.min).cwiseMin(box.max);
  const double gap = out.norm();
  if (!(gap > 1e-12)) return spheres;
  // The box lies behind the plane through its nearest point normal to `out`.
  const double along = gap - SupportAlong(a, pose_a.linear(), -out / gap);
  return Tightened(spheres, along);
}

}  // namespace stairplan
