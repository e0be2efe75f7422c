// A point cloud: the raw 3-D points a depth sensor returns, in the world frame, and the reader
// that loads one from a file (PLY, PCD or whitespace XYZ text, chosen by the file's content).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// Points in the world frame [m]. Every point is finite (the readers and the sensor guarantee it).
struct PointCloud {
  std::vector<Eigen::Vector3d> points;  ///< the points [m]

  /// Number of points.
  std::size_t size() const { return points.size(); }
  /// True when there are no points.
  bool empty() const { return points.empty(); }
  ///@{
  /// Componentwise bounds; both zero for an empty cloud.
  Eigen::Vector3d Min() const;
  Eigen::Vector3d Max() const;
  ///@}
};

/// The cloud rotated by `yaw` about z, then translated: p_W = Rz(yaw) p + translation.
PointCloud TransformCloud(const PointCloud& cloud, double yaw, const Eigen::Vector3d& translation);

/// The cloud file formats ReadPointCloud() reads.
enum class CloudFormat { kPly, kPcd, kXyz };

/// The format of a cloud file by its content: a "ply" first line, a PCD header (comments, then
/// VERSION or FIELDS); failing both, the extension (`.ply`, `.pcd`: that reader's error then
/// says what is wrong), else XYZ text.
CloudFormat DetectCloudFormat(const std::string& bytes, const std::string& path);

/// The bytes of a cloud file; a file that cannot be opened is a FieldError naming the path.
std::string ReadCloudFile(const std::string& path);

/// Parses a cloud in the format DetectCloudFormat finds; `source` names it in errors.
PointCloud ParsePointCloud(const std::string& bytes, const std::string& source);

/// Reads a PLY, PCD or XYZ file (ParsePointCloud). Errors are FieldError naming the file and the
/// line, header field or point; a missing file or one with no points is an error.
PointCloud ReadPointCloud(const std::string& path);

}  // namespace stairplan
