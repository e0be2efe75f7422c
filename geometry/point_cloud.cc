#include "geometry/point_cloud.h"

#include <cctype>

#include <Eigen/Geometry>

#include "geometry/ply_io.h"
#include "geometry/xyz_io.h"

namespace stairplan {

Eigen::Vector3d PointCloud::Min() const {
  if (points.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = points.front();
  for (const auto& p : points) lo = lo.cwiseMin(p);
  return lo;
}

Eigen::Vector3d PointCloud::Max() const {
  if (points.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = points.front();
  for (const auto& p : points) hi = hi.cwiseMax(p);
  return hi;
}

PointCloud TransformCloud(const PointCloud& cloud, double yaw, const Eigen::Vector3d& translation) {
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  PointCloud out;
  out.points.reserve(cloud.size());
  for (const auto& p : cloud.points) out.points.push_back(rotation * p + translation);
  return out;
}

PointCloud ReadPointCloud(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == "ply" ? ReadPly(path) : ReadXyz(path);
}

}  // namespace stairplan
