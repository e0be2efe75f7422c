// Small geometric value types shared by the geometry module: polygons and boxes.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// A closed interval [lo, hi] along one axis.
struct Extent {
  double lo = 0.0;  ///< lower end
  double hi = 0.0;  ///< upper end
};

/// A convex polygon in the xy plane at height z, vertices counter-clockwise.
struct Polygon2 {
  std::vector<Eigen::Vector2d> vertices;  ///< the corners, counter-clockwise [m]
  double z = 0.0;  ///< the plane's height [m]

  /// True when p lies inside or on the boundary (within tol).
  bool Contains(const Eigen::Vector2d& p, double tol = 1e-12) const;
  /// The closest point of the polygon to p (p itself when inside).
  Eigen::Vector2d ClosestPoint(const Eigen::Vector2d& p) const;
  /// Distance from p to the polygon: 0 inside.
  double Distance(const Eigen::Vector2d& p) const;
  /// Signed distance: negative inside (depth to the boundary), positive outside.
  double SignedDistance(const Eigen::Vector2d& p) const;
  /// The enclosed area [m^2].
  double Area() const;
  /// The polygon's extent along x (step regions are rectangles along the flight).
  Extent XExtent() const;
  /// True when the polygon has fewer than three vertices and so encloses nothing.
  bool empty() const { return vertices.size() < 3; }
};

/// The convex hull of `points` (counter-clockwise; fewer than three vertices when degenerate).
Polygon2 ConvexHull(std::vector<Eigen::Vector2d> points);

/// An axis-aligned rectangle [x0,x1] x [y0,y1], as a convex polygon.
Polygon2 Rectangle(double x0, double x1, double y0, double y1, double z);

/// What a stair solid is, for collision reports and drawing.
enum class SolidKind { kBlock, kNosing };

/// An axis-aligned box.
struct Box3 {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< the corner with the smallest coordinates [m]
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  ///< the corner with the largest coordinates [m]
  SolidKind kind = SolidKind::kBlock;  ///< a tread block or a nosing lip
  int surface_index = 0;  ///< the surface (block) or edge (nosing) it belongs to

  /// The box's centre [m].
  Eigen::Vector3d Center() const { return 0.5 * (min + max); }
  /// The box's side lengths [m].
  Eigen::Vector3d Size() const { return max - min; }
  /// Signed distance from p: negative inside.
  double SignedDistance(const Eigen::Vector3d& p) const;
};

}  // namespace stairplan
