#include "stairplan/collision/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace stairplan {
namespace {

// qhull reports through a FILE*; the library never prints, so its messages go to memory and
// into the exception.
class MemoryFile {
 public:
  MemoryFile() : file_(open_memstream(&buffer_, &size_)) {}
  ~MemoryFile() {
    if (file_) std::fclose(file_);
    std::free(buffer_);
  }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  FILE* get() const { return file_; }
  std::string text() {
    if (file_) std::fflush(file_);
    std::string all = buffer_ ? std::string(buffer_, size_) : "";
    const std::size_t end = all.find('\n');
    return all.substr(0, end);  // qhull's first line names the problem
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d ClosestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

MeshHull ComputeConvexHull(const std::vector<Eigen::Vector3d>& points, const std::string& name) {
  if (points.size() < 4) {
    throw std::invalid_argument(name + ": " + std::to_string(points.size()) + " vertices span no volume; a convex hull needs 4");
  }
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Eigen::Vector3d& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  MemoryFile errors;
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, errors.get());
  char options[] = "qhull Qt";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, options,
                                     nullptr, errors.get());
  MeshHull hull;
  if (exit_code == 0) {
    std::vector<int> index_of(points.size(), -1);
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> triangle{};
      int k = 0;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k == 3) break;
        const int id = qh_pointid(qh, vertex->point);
        int& slot = index_of[static_cast<std::size_t>(id)];
        if (slot < 0) {
          slot = static_cast<int>(hull.vertices.size());
          hull.vertices.push_back(points[static_cast<std::size_t>(id)]);
        }
        triangle[static_cast<std::size_t>(k++)] = slot;
      }
      if (k != 3) continue;
      const Eigen::Vector3d& a = hull.vertices[static_cast<std::size_t>(triangle[0])];
      const Eigen::Vector3d n = (hull.vertices[static_cast<std::size_t>(triangle[1])] - a)
                                    .cross(hull.vertices[static_cast<std::size_t>(triangle[2])] - a);
      if (n.dot(Eigen::Vector3d(facet->normal[0], facet->normal[1], facet->normal[2])) < 0.0) std::swap(triangle[1], triangle[2]);
      hull.triangles.push_back(triangle);
    }
  }
  const std::string message = errors.text();
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0, total_long = 0;
  qh_memfreeshort(qh, &still_long, &total_long);
  if (exit_code != 0 || hull.triangles.size() < 4) {
    throw std::invalid_argument(name + ": the mesh's convex hull has no volume (its vertices lie in one plane or on one line)" +
                                (message.empty() ? "" : ": qhull: " + message));
  }
  return hull;
}

double HullExcess(const MeshHull& hull, const std::vector<Eigen::Vector3d>& vertices,
                  const std::vector<std::array<int, 3>>& triangles, double spacing) {
  if (!(spacing > 0.0)) throw std::invalid_argument("HullExcess: spacing must be positive");
  const auto distance_to_mesh = [&](const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : triangles) {
      const Eigen::Vector3d q = ClosestOnTriangle(p, vertices[static_cast<std::size_t>(t[0])],
                                                  vertices[static_cast<std::size_t>(t[1])], vertices[static_cast<std::size_t>(t[2])]);
      best = std::min(best, (q - p).squaredNorm());
    }
    return std::sqrt(best);
  };
  double excess = 0.0;
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d& a = hull.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = hull.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = hull.vertices[static_cast<std::size_t>(t[2])];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    // Barycentric grid: neighbouring samples are at most longest / n apart, every point of the
    // triangle within that of a sample.
    const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n) + (c - a) * (static_cast<double>(j) / n);
        excess = std::max(excess, distance_to_mesh(p));
      }
    }
  }
  return excess + spacing;
}

}  // namespace stairplan
