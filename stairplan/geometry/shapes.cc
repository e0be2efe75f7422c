#include "stairplan/geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stairplan {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

Eigen::Vector2d ClosestOnSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

}  // namespace

bool Polygon2::Contains(const Eigen::Vector2d& p, double tol) const {
  if (empty()) return false;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = vertices[i];
    const Eigen::Vector2d& b = vertices[(i + 1) % n];
    const Eigen::Vector2d edge = b - a;
    const double len = edge.norm();
    if (len <= 0.0) continue;
    if (Cross(edge, p - a) / len < -tol) return false;
  }
  return true;
}

Eigen::Vector2d Polygon2::ClosestPoint(const Eigen::Vector2d& p) const {
  if (vertices.empty()) return p;
  if (Contains(p)) return p;
  Eigen::Vector2d best = vertices.front();
  double best_d2 = std::numeric_limits<double>::infinity();
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d q = ClosestOnSegment(vertices[i], vertices[(i + 1) % n], p);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

double Polygon2::Distance(const Eigen::Vector2d& p) const { return (ClosestPoint(p) - p).norm(); }

double Polygon2::SignedDistance(const Eigen::Vector2d& p) const {
  if (!Contains(p)) return Distance(p);
  double depth = std::numeric_limits<double>::infinity();
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    depth = std::min(depth, (ClosestOnSegment(vertices[i], vertices[(i + 1) % n], p) - p).norm());
  }
  return -depth;
}

Extent Polygon2::XExtent() const {
  Extent e{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& v : vertices) {
    e.lo = std::min(e.lo, v.x());
    e.hi = std::max(e.hi, v.x());
  }
  return e;
}

double Polygon2::Area() const {
  double twice = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) twice += Cross(vertices[i], vertices[(i + 1) % n]);
  return 0.5 * twice;
}

// Andrew's monotone chain.
Polygon2 ConvexHull(std::vector<Eigen::Vector2d> points) {
  if (points.size() < 3) return Polygon2{points, 0.0};
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  Polygon2 polygon;
  polygon.vertices = hull;
  return polygon;
}

Polygon2 Rectangle(double x0, double x1, double y0, double y1, double z) {
  Polygon2 poly;
  poly.z = z;
  poly.vertices = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return poly;
}

double Box3::SignedDistance(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d center = Center();
  const Eigen::Vector3d half = 0.5 * Size();
  const Eigen::Vector3d q = (p - center).cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

}  // namespace stairplan
