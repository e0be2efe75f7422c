// A point cloud: the raw 3-D points a depth sensor returns, in the world frame, and the readers
// that load one from a file (PLY or whitespace XYZ text, chosen by the file's extension).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// Points in the world frame [m]. Every point is finite (the readers and the sensor guarantee it).
struct PointCloud {
  std::vector<Eigen::Vector3d> points;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  /// Componentwise bounds; both zero for an empty cloud.
  Eigen::Vector3d Min() const;
  Eigen::Vector3d Max() const;
};

/// The cloud rotated by `yaw` about z, then translated: p_W = Rz(yaw) p + translation.
PointCloud TransformCloud(const PointCloud& cloud, double yaw, const Eigen::Vector3d& translation);

/// Reads a PLY file (`.ply`) or whitespace XYZ text (anything else). Errors are FieldError naming
/// the file and the line (or the vertex of a binary PLY); a file with no points is an error.
PointCloud ReadPointCloud(const std::string& path);

}  // namespace stairplan
