// The synthetic depth sensor: hits lie on the stairs' surfaces, the noise has the asked-for
// spread, scans repeat with a seed, and the occlusions a real sensor has are there.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/perception/depth_sensor.h"
#include "perception/perception_scenes.h"

using namespace stairplan;

namespace {

// Distance from p to the surface of the union of the solids (0 on a face).
double DistanceToSolids(const std::vector<Box3>& solids, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Box3& b : solids) best = std::min(best, std::abs(b.SignedDistance(p)));
  return best;
}

}  // namespace

TEST_CASE("noise-free camera hits lie on the stairs and none inside them", "[sensor]") {
  const Staircase stairs(StairSpec{});
  SensorNoise noise;
  noise.range_sigma = 0.0;
  const PointCloud cloud = ScanStairs(stairs, stairplan::testing::SmallCamera(), stairplan::testing::CameraOnBottomLanding(), noise);
  REQUIRE(cloud.size() > 3000);
  const auto solids = stairs.Solids();
  for (const auto& p : cloud.points) {
    REQUIRE(DistanceToSolids(solids, p) < 1e-9);
    for (const Box3& b : solids) REQUIRE(b.SignedDistance(p) > -1e-9);
  }
}

TEST_CASE("range noise has the requested spread and a seed repeats a scan", "[sensor]") {
  const Staircase stairs(StairSpec{});
  const auto camera = stairplan::testing::SmallCamera();
  const auto pose = stairplan::testing::CameraOnBottomLanding();
  SensorNoise exact;
  exact.range_sigma = 0.0;
  SensorNoise noisy;
  noisy.range_sigma = 0.01;
  noisy.seed = 9;
  const PointCloud a = ScanStairs(stairs, camera, pose, exact);
  const PointCloud b = ScanStairs(stairs, camera, pose, noisy);
  const PointCloud c = ScanStairs(stairs, camera, pose, noisy);
  REQUIRE(a.size() == b.size());
  double sum2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Noise moves a point along its ray: the range changes, the direction does not.
    const Eigen::Vector3d ra = a.points[i] - pose.position, rb = b.points[i] - pose.position;
    REQUIRE(ra.normalized().dot(rb.normalized()) > 1.0 - 1e-9);
    sum2 += std::pow(rb.norm() - ra.norm(), 2);
    REQUIRE(b.points[i] == c.points[i]);
  }
  CHECK(std::sqrt(sum2 / a.size()) == Approx(0.01).epsilon(0.05));
}

TEST_CASE("looking down the stairs, the tread just below each nosing is hidden", "[sensor]") {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  const SensorPose pose = stairplan::testing::CameraOnTopLanding(stairs);
  SensorNoise noise;
  noise.range_sigma = 0.0;
  const PointCloud cloud = ScanStairs(stairs, stairplan::testing::SmallCamera(), pose, noise);
  // Descending, tread k spans [x_begin, x_end]; the part right after x_begin sits under the
  // riser's shadow (behind the nosing of the surface above). Count points there per tread.
  for (int k = 1; k < stairs.steps(); ++k) {
    const StairSurface& s = stairs.surface(k);
    int hidden = 0, visible = 0;
    for (const auto& p : cloud.points) {
      if (std::abs(p.z() - s.z) > 1e-6 || std::abs(p.y()) > 0.3) continue;
      if (p.x() > s.x_begin && p.x() < s.x_begin + 0.05) ++hidden;
      if (p.x() > s.x_end - 0.05 && p.x() < s.x_end) ++visible;
    }
    INFO("tread " << k);
    CHECK(hidden == 0);
    CHECK(visible > 0);
  }
}

TEST_CASE("a spinning lidar sees the flight all around and the same seed repeats", "[sensor]") {
  const Staircase stairs(StairSpec{});
  SensorPose pose;
  pose.position = Eigen::Vector3d(0.8, 0.0, 2.0);  // above the flight
  SpinningLidar lidar;
  lidar.min_elevation = -1.2;
  lidar.max_elevation = 0.2;
  const PointCloud a = ScanStairs(stairs, lidar, pose);
  const PointCloud b = ScanStairs(stairs, lidar, pose);
  REQUIRE(a.size() > 1000);
  CHECK(a.points == b.points);
  // Beams reach both landings from the middle of the flight.
  int before = 0, after = 0;
  for (const auto& p : a.points) {
    before += p.x() < -0.2 ? 1 : 0;
    after += p.x() > stairs.edges().back().x_riser + 0.1 ? 1 : 0;
  }
  CHECK(before > 0);
  CHECK(after > 0);
}

TEST_CASE("sensor settings out of range are rejected by name", "[sensor]") {
  const Staircase stairs(StairSpec{});
  PinholeCamera camera;
  camera.horizontal_fov = 0.0;
  CHECK_THROWS_WITH(ScanStairs(stairs, camera, SensorPose{}), Catch::Contains("horizontal_fov"));
  SensorNoise noise;
  noise.range_sigma = -1.0;
  CHECK_THROWS_WITH(ScanStairs(stairs, PinholeCamera{}, SensorPose{}, noise), Catch::Contains("range_sigma"));
}
