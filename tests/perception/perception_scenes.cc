#include "perception/perception_scenes.h"

namespace stairplan::testing {

SensorPose CameraOnBottomLanding() {
  SensorPose pose;
  pose.position = Eigen::Vector3d(-0.8, 0.0, 0.5);
  pose.yaw = 0.0;
  pose.pitch = -0.08;  // the lower edge of the view reaches the landing, the upper one the top riser
  return pose;
}

SensorPose CameraOnTopLanding(const Staircase& stairs) {
  SensorPose pose;
  pose.position = Eigen::Vector3d(-0.3, 0.0, stairs.total_rise() + 0.6);
  pose.pitch = -0.7;
  return pose;
}

PinholeCamera VgaCamera() {
  PinholeCamera camera;
  camera.width_px = 640;
  camera.height_px = 480;
  return camera;
}

PinholeCamera SmallCamera() {
  PinholeCamera camera;
  camera.width_px = 128;
  camera.height_px = 96;
  return camera;
}

Scene ScanFromBottom(const Staircase& stairs, double yaw, const Eigen::Vector3d& offset, double sigma, std::uint32_t seed) {
  SensorNoise noise;
  noise.range_sigma = sigma;
  noise.seed = seed;
  Scene scene;
  scene.cloud = TransformCloud(ScanStairs(stairs, SmallCamera(), CameraOnBottomLanding(), noise), yaw, offset);
  scene.yaw = yaw;
  scene.offset = offset;
  return scene;
}

StairSpec RandomCodeStairs(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  StairSpec spec;
  spec.steps = 3 + static_cast<int>(unit(rng) * 7.0);
  spec.rise = 0.10 + 0.10 * unit(rng);
  spec.run = 0.22 + 0.13 * unit(rng);
  spec.nosing = 0.032 * unit(rng);
  spec.width = 0.8 + 0.7 * unit(rng);
  return spec;
}

}  // namespace stairplan::testing
