// Synthetic scenes shared by the perception tests: stairs seen by a camera standing on the bottom
// landing, placed in the world with a yaw and an offset, plus random building-code staircases.
#pragma once

#include <random>

#include "stairplan/perception/depth_sensor.h"
#include "stairplan/perception/point_cloud.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan::testing {

/// A camera 0.5 m above the bottom landing, 0.8 m before the first riser, looking up the flight.
SensorPose CameraOnBottomLanding();
/// A camera 0.6 m above the top landing of `stairs` (a descent), 0.3 m before its edge, looking
/// down the flight.
SensorPose CameraOnTopLanding(const Staircase& stairs);
/// The test camera: 128 x 96 rays, so a hundred scans stay fast.
PinholeCamera SmallCamera();
/// A depth camera's VGA mode, 640 x 480 rays. Looking down a flight from its top, coarser images
/// leave the bottom landing's cells more than 20 cm from any return: poor data, no step region.
PinholeCamera VgaCamera();

/// A scan of `stairs` (in its own frame) moved into the world by yaw and offset.
struct Scene {
  PointCloud cloud;     ///< world frame
  double yaw = 0.0;     ///< the stairs' ascending heading in the world
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};
Scene ScanFromBottom(const Staircase& stairs, double yaw, const Eigen::Vector3d& offset, double sigma, std::uint32_t seed);

/// A random staircase within building-code ranges (rise 0.10-0.20, run 0.22-0.35, 3-9 steps).
StairSpec RandomCodeStairs(std::mt19937& rng);

}  // namespace stairplan::testing
