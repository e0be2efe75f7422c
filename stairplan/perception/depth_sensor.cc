#include "stairplan/perception/depth_sensor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace stairplan {
namespace {

// Axes of a sensor frame: forward along the optical axis, left, and up, right-handed.
struct Axes {
  Eigen::Vector3d forward, left, up;
};

Axes SensorAxes(const SensorPose& pose) {
  const double cy = std::cos(pose.yaw), sy = std::sin(pose.yaw);
  const double cp = std::cos(pose.pitch), sp = std::sin(pose.pitch);
  Axes a;
  a.forward = Eigen::Vector3d(cp * cy, cp * sy, sp);
  a.left = Eigen::Vector3d(-sy, cy, 0.0);
  a.up = a.forward.cross(a.left);
  return a;
}

void RequirePositive(const char* what, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("ScanStairs: ") + what + " must be positive and finite");
  }
}

void CheckPose(const SensorPose& pose, const SensorNoise& noise) {
  if (!pose.position.allFinite() || !std::isfinite(pose.yaw) || !std::isfinite(pose.pitch)) {
    throw std::invalid_argument("ScanStairs: the sensor pose must be finite");
  }
  if (!(noise.range_sigma >= 0.0) || !std::isfinite(noise.range_sigma)) {
    throw std::invalid_argument("ScanStairs: noise.range_sigma must be >= 0");
  }
}

// Casts every ray and keeps the hits within range, with range noise.
template <typename RayFn>
PointCloud Cast(const std::vector<Box3>& solids, const SensorPose& pose, const SensorNoise& noise, int count, double max_range, RayFn ray) {
  std::mt19937 rng(noise.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PointCloud cloud;
  cloud.points.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d direction = ray(i).normalized();
    const double t = RayCast(solids, pose.position, direction);
    if (!(t <= max_range)) continue;
    const double noisy = t + noise.range_sigma * gauss(rng);
    cloud.points.push_back(pose.position + noisy * direction);
  }
  return cloud;
}

}  // namespace

double RayCast(const std::vector<Box3>& solids, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const Box3& box : solids) {
    double t_enter = 0.0, t_exit = best;
    bool hit = true;
    for (int axis = 0; axis < 3 && hit; ++axis) {
      const double d = direction[axis];
      if (std::abs(d) < 1e-15) {
        hit = origin[axis] >= box.min[axis] && origin[axis] <= box.max[axis];
        continue;
      }
      double t0 = (box.min[axis] - origin[axis]) / d;
      double t1 = (box.max[axis] - origin[axis]) / d;
      if (t0 > t1) std::swap(t0, t1);
      t_enter = std::max(t_enter, t0);
      t_exit = std::min(t_exit, t1);
      hit = t_enter <= t_exit;
    }
    if (hit && t_enter > 0.0 && t_enter < best) best = t_enter;
  }
  return best;
}

PointCloud ScanStairs(const Staircase& stairs, const PinholeCamera& camera, const SensorPose& pose, const SensorNoise& noise) {
  return ScanSolids(stairs.Solids(), camera, pose, noise);
}

PointCloud ScanStairs(const Staircase& stairs, const SpinningLidar& lidar, const SensorPose& pose, const SensorNoise& noise) {
  return ScanSolids(stairs.Solids(), lidar, pose, noise);
}

PointCloud ScanSolids(const std::vector<Box3>& solids, const PinholeCamera& camera, const SensorPose& pose, const SensorNoise& noise) {
  CheckPose(pose, noise);
  if (camera.width_px < 1 || camera.height_px < 1) throw std::invalid_argument("ScanStairs: camera image size must be >= 1 pixel");
  RequirePositive("camera.horizontal_fov", camera.horizontal_fov);
  RequirePositive("camera.vertical_fov", camera.vertical_fov);
  RequirePositive("camera.max_range", camera.max_range);
  const Axes a = SensorAxes(pose);
  const double tx = std::tan(0.5 * camera.horizontal_fov), ty = std::tan(0.5 * camera.vertical_fov);
  return Cast(solids, pose, noise, camera.width_px * camera.height_px, camera.max_range, [&](int i) {
    const int u = i % camera.width_px, v = i / camera.width_px;
    const double sx = 1.0 - 2.0 * (u + 0.5) / camera.width_px;  // +1 at the left edge
    const double sy = 1.0 - 2.0 * (v + 0.5) / camera.height_px; // +1 at the top edge
    return Eigen::Vector3d(a.forward + sx * tx * a.left + sy * ty * a.up);
  });
}

PointCloud ScanSolids(const std::vector<Box3>& solids, const SpinningLidar& lidar, const SensorPose& pose, const SensorNoise& noise) {
  CheckPose(pose, noise);
  if (lidar.beams < 1 || lidar.azimuth_steps < 1) throw std::invalid_argument("ScanStairs: lidar beams and azimuth_steps must be >= 1");
  RequirePositive("lidar.max_range", lidar.max_range);
  if (!(lidar.max_elevation >= lidar.min_elevation)) throw std::invalid_argument("ScanStairs: lidar.max_elevation must be >= min_elevation");
  const Axes a = SensorAxes(pose);
  return Cast(solids, pose, noise, lidar.beams * lidar.azimuth_steps, lidar.max_range, [&](int i) {
    const int beam = i / lidar.azimuth_steps, step = i % lidar.azimuth_steps;
    const double elevation = lidar.beams == 1 ? lidar.min_elevation
                                              : lidar.min_elevation + (lidar.max_elevation - lidar.min_elevation) * beam / (lidar.beams - 1);
    const double azimuth = 2.0 * M_PI * step / lidar.azimuth_steps;
    const double ce = std::cos(elevation);
    return Eigen::Vector3d(ce * std::cos(azimuth) * a.forward + ce * std::sin(azimuth) * a.left + std::sin(elevation) * a.up);
  });
}

}  // namespace stairplan
