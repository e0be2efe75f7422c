#include "stairplan/perception/point_cloud.h"

#include <cctype>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/pcd_io.h"
#include "stairplan/perception/ply_io.h"
#include "stairplan/perception/xyz_io.h"

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

CloudFormat DetectCloudFormat(const std::string& bytes, const std::string& path) {
  if (bytes.compare(0, 4, "ply\n") == 0 || bytes.compare(0, 5, "ply\r\n") == 0) return CloudFormat::kPly;
  if (LooksLikePcd(bytes)) return CloudFormat::kPcd;
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "ply") return CloudFormat::kPly;
  if (ext == "pcd") return CloudFormat::kPcd;
  return CloudFormat::kXyz;
}

PointCloud ParsePointCloud(const std::string& bytes, const std::string& source) {
  switch (DetectCloudFormat(bytes, source)) {
    case CloudFormat::kPly: return ParsePly(bytes, source);
    case CloudFormat::kPcd: return ParsePcd(bytes, source);
    case CloudFormat::kXyz: break;
  }
  return ParseXyz(bytes, source);
}

std::string ReadCloudFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FieldError(path, "cannot open the point cloud file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

PointCloud ReadPointCloud(const std::string& path) { return ParsePointCloud(ReadCloudFile(path), path); }

}  // namespace stairplan
