// The stair tracker (seed 000 [0071]) on synthetic camera clouds: the canonical flight and a
// hundred random building-code flights placed anywhere in the world, and terrain that is not
// stairs (a ramp, a flat floor, a box) rejected.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "stairplan/perception/stair_tracker.h"
#include "perception/perception_scenes.h"

using namespace stairplan;
using stairplan::testing::ScanFromBottom;

namespace {

constexpr double kDeg = M_PI / 180.0;

double YawError(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

// A grid of points with Gaussian height noise over [x0, x1] x [-0.6, 0.6].
template <typename Fn>
PointCloud GridCloud(double x0, double x1, Fn height, double sigma, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  PointCloud cloud;
  for (double x = x0; x <= x1; x += 0.015) {
    for (double y = -0.6; y <= 0.6; y += 0.015) cloud.points.emplace_back(x, y, height(x) + noise(rng));
  }
  return cloud;
}

}  // namespace

TEST_CASE("tracker: 7 steps of 0.17 x 0.27 seen from the bottom landing", "[tracker]") {
  const Staircase stairs(StairSpec{});
  for (const double yaw : {0.0, 0.7, -2.5}) {
    const Eigen::Vector3d offset(3.0 * std::cos(yaw + 1.0), -2.0, 0.4);
    const auto scene = ScanFromBottom(stairs, yaw, offset, 0.005, 17);
    const StairFit fit = FitStairs(scene.cloud);
    INFO("yaw " << yaw << ": " << fit.reason);
    REQUIRE(fit.found);
    CHECK(fit.model.steps == 7);
    CHECK(std::abs(fit.model.rise - 0.17) <= 0.005);
    CHECK(std::abs(fit.model.run - 0.27) <= 0.005);
    CHECK(YawError(fit.model.yaw(), yaw) <= 1.0 * kDeg);
    CHECK(fit.model.width == Approx(1.0).margin(0.05));
    CHECK(fit.level_rms < 0.02);
    CHECK(fit.point_rms < 0.02);
    CHECK(fit.tread_points > 100);
    // The fitted edges lie on the true walking edges (nosing fronts), moved into the world.
    const auto edges = fit.model.Edges();
    REQUIRE(edges.size() == 7u);
    const Eigen::Vector2d dir(std::cos(yaw), std::sin(yaw));
    for (int k = 0; k < 7; ++k) {
      const Eigen::Vector3d mid = 0.5 * (edges[k].a + edges[k].b);
      const double along = (mid.head<2>() - offset.head<2>()).dot(dir);
      CHECK(along == Approx(stairs.edges()[k].x_nose).margin(0.02));
      CHECK(mid.z() - offset.z() == Approx(stairs.edges()[k].z_high).margin(0.02));
    }
  }
}

TEST_CASE("tracker: at least 95 of 100 random building-code flights within the bounds", "[tracker]") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int good = 0;
  for (int i = 0; i < 100; ++i) {
    const StairSpec spec = stairplan::testing::RandomCodeStairs(rng);
    const double yaw = (2.0 * unit(rng) - 1.0) * M_PI;
    const Eigen::Vector3d offset(10.0 * unit(rng) - 5.0, 10.0 * unit(rng) - 5.0, unit(rng) - 0.5);
    const auto scene = ScanFromBottom(Staircase(spec), yaw, offset, 0.005, 1000 + i);
    const StairFit fit = FitStairs(scene.cloud);
    const bool ok = fit.found && fit.model.steps == spec.steps && std::abs(fit.model.rise - spec.rise) <= 0.005 &&
                    std::abs(fit.model.run - spec.run) <= 0.005 && YawError(fit.model.yaw(), yaw) <= 1.0 * kDeg;
    if (!ok) WARN("flight " << i << " missed: steps " << spec.steps << " rise " << spec.rise << " run " << spec.run << " (" << fit.reason << ")");
    good += ok ? 1 : 0;
  }
  CHECK(good >= 95);
}

TEST_CASE("tracker rejects a ramp, a flat floor and a single box", "[tracker]") {
  const PointCloud ramp = GridCloud(-1.0, 2.5, [](double x) { return std::clamp(0.63 * x, 0.0, 1.19); }, 0.005, 1);
  const StairFit on_ramp = FitStairs(ramp);
  CHECK_FALSE(on_ramp.found);
  CHECK_THAT(on_ramp.reason, Catch::Contains("ramp"));

  const StairFit on_floor = FitStairs(GridCloud(-1.0, 2.5, [](double) { return 0.0; }, 0.005, 2));
  CHECK_FALSE(on_floor.found);
  CHECK_THAT(on_floor.reason, Catch::Contains("flat"));

  Box3 floor, box;
  floor.min = {-3.0, -3.0, -0.1};
  floor.max = {5.0, 3.0, 0.0};
  box.min = {0.5, -0.3, 0.0};
  box.max = {1.1, 0.3, 0.2};
  const PointCloud kerb = ScanSolids({floor, box}, stairplan::testing::SmallCamera(), stairplan::testing::CameraOnBottomLanding());
  const StairFit on_box = FitStairs(kerb);
  CHECK_FALSE(on_box.found);
  CHECK_THAT(on_box.reason, Catch::Contains("risers") || Catch::Contains("one direction"));
}

TEST_CASE("tracker: descending view from the top landing finds the same flight", "[tracker]") {
  StairSpec spec;
  const Staircase stairs(spec);
  SensorPose pose;
  // Near the top edge, looking back down the flight (towards -x): from further back the flight
  // hides behind its top nosing.
  pose.position = Eigen::Vector3d(stairs.edges().back().x_riser + 0.3, 0.0, stairs.total_rise() + 0.6);
  pose.yaw = M_PI;
  pose.pitch = -0.7;
  SensorNoise noise;
  noise.range_sigma = 0.005;
  const PointCloud cloud = ScanStairs(stairs, stairplan::testing::SmallCamera(), pose, noise);
  const StairFit fit = FitStairs(cloud);
  INFO(fit.reason);
  REQUIRE(fit.found);
  CHECK(fit.model.steps == 7);
  CHECK(std::abs(fit.model.rise - 0.17) <= 0.005);
  // From above, the far treads are sampled a few centimetres apart along the flight, so the far
  // edges are only that exact; the run stays within a centimetre.
  CHECK(std::abs(fit.model.run - 0.27) <= 0.01);
  CHECK(YawError(fit.model.yaw(), 0.0) <= 1.0 * kDeg);  // the direction is the ascending one
}

TEST_CASE("tracker misuse: an empty cloud or bad settings throw", "[tracker]") {
  CHECK_THROWS_AS(FitStairs(PointCloud{}), std::invalid_argument);
  StairTrackerSettings settings;
  settings.min_rise = 0.5;
  PointCloud one;
  one.points.emplace_back(0, 0, 0);
  CHECK_THROWS_WITH(FitStairs(one, settings), Catch::Contains("min_rise"));
}
