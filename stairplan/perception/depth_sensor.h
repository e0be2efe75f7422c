// A synthetic depth sensor: ray-casts a pinhole camera or a spinning lidar from a pose onto a
// Staircase's solids, so the cloud has the holes a real sensor leaves (treads hidden behind
// nosings when looking down, tread tops unseen above the sensor when looking up). Range noise is
// Gaussian along each ray with a fixed seed, so tests are repeatable.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "stairplan/perception/point_cloud.h"
#include "stairplan/geometry/shapes.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// Where the sensor is and where it looks, in the staircase's frame. Pitch > 0 looks up.
struct SensorPose {
  Eigen::Vector3d position = Eigen::Vector3d(-0.8, 0.0, 0.5);  ///< the optical centre [m]
  double yaw = 0.0;    ///< heading of the optical axis about z [rad]
  double pitch = 0.0;  ///< elevation of the optical axis [rad]
};

/// A pinhole depth camera: one ray per pixel.
struct PinholeCamera {
  int width_px = 160;  ///< image width [pixels]
  int height_px = 120;  ///< image height [pixels]
  double horizontal_fov = 1.5;  ///< [rad]
  double vertical_fov = 1.2;    ///< [rad]
  double max_range = 8.0;       ///< returns beyond this are dropped [m]
};

/// A spinning multi-beam lidar: beams spread evenly in elevation, swept through 360 degrees.
struct SpinningLidar {
  int beams = 16;  ///< number of beams
  double min_elevation = -0.5;  ///< [rad], relative to the pose's pitch
  double max_elevation = 0.25;  ///< [rad]
  int azimuth_steps = 720;  ///< rays per beam over a turn
  double max_range = 20.0;      ///< [m]
};

/// Range noise of a scan.
struct SensorNoise {
  double range_sigma = 0.005;  ///< standard deviation of the range error [m]
  std::uint32_t seed = 1;  ///< random seed: the same seed gives the same cloud
};

/// Distance along the unit ray (origin, direction) to the nearest box, or +infinity.
double RayCast(const std::vector<Box3>& solids, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

///@{
/// Scans any set of boxes (a floor, a kerb, a staircase's Solids()) with a camera or a lidar.
PointCloud ScanSolids(const std::vector<Box3>& solids, const PinholeCamera& camera, const SensorPose& pose, const SensorNoise& noise = {});
PointCloud ScanSolids(const std::vector<Box3>& solids, const SpinningLidar& lidar, const SensorPose& pose, const SensorNoise& noise = {});
///@}

/// Scans the stairs with a camera. Throws std::invalid_argument for a non-positive image size,
/// field of view or range, or a negative noise sigma.
PointCloud ScanStairs(const Staircase& stairs, const PinholeCamera& camera, const SensorPose& pose, const SensorNoise& noise = {});
/// Scans the stairs with a spinning lidar (same error rules).
PointCloud ScanStairs(const Staircase& stairs, const SpinningLidar& lidar, const SensorPose& pose, const SensorNoise& noise = {});

}  // namespace stairplan
