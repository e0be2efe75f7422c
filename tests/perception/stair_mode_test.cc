// Stair mode and the alignment pose (seed 001 [0042]-[0043], claims 6-9).
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/geometry/stair_mode.h"
#include "perception/footfall_scenes.h"

using namespace stairplan;

namespace {

StairModel DefaultFlight(double yaw = 0.0, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  return ModelOfStaircase(Staircase(StairSpec{}), origin, yaw);
}

}  // namespace

TEST_CASE("stair mode: distance to a flight's footprint", "[stairmode]") {
  const StairModel m = DefaultFlight();  // first edge at x = -0.02, last at 1.60, |y| <= 0.5
  CHECK(DistanceToFlight(m, Eigen::Vector2d(0.5, 0.2)) == Approx(0.0));
  CHECK(DistanceToFlight(m, Eigen::Vector2d(-1.02, 0.0)) == Approx(1.0));
  CHECK(DistanceToFlight(m, Eigen::Vector2d(0.5, 1.5)) == Approx(1.0));
  CHECK(DistanceToFlight(m, Eigen::Vector2d(2.6, 0.0)) == Approx(1.0));
  CHECK(DistanceToFlight(m, Eigen::Vector2d(-0.32, 0.9)) == Approx(0.5));
}

TEST_CASE("stair mode engages within the distance and releases with hysteresis", "[stairmode]") {
  StairModeSettings settings;
  settings.engage_distance = 1.0;
  settings.release_distance = 1.5;
  // Two flights: one ascending +x from x = -0.02, one ascending -x from x = -5.98 to -7.60.
  StairMode mode({DefaultFlight(), DefaultFlight(M_PI, Eigen::Vector3d(-6.0, 0.0, 0.0))}, settings);
  // Walking from x = -8.5 (beyond the second flight) towards the first one.
  for (double x = -8.5; x <= 0.0; x += 0.01) {
    const int engaged = mode.Update(Eigen::Vector2d(x, 0.0));
    INFO("x = " << x);
    if (x < -8.6 + 1e-9 || (x > -7.6 - 1.0 + 0.005 && x < -4.98 - 0.005)) CHECK(engaged == 1);
    if (x > -4.98 + 1.5 + 0.005 && x < -1.02 - 0.005) CHECK(engaged == -1);
    if (x > -1.02 + 0.005) CHECK(engaged == 0);
  }
  // Backing away: still on until past the release distance.
  CHECK(mode.Update(Eigen::Vector2d(-1.4, 0.0)) == 0);
  CHECK(mode.Update(Eigen::Vector2d(-1.53, 0.0)) == -1);
  CHECK_FALSE(mode.active());
  StairModeSettings bad;
  bad.release_distance = 0.5;
  CHECK_THROWS_WITH(StairMode({}, bad), Catch::Contains("release_distance"));
}

TEST_CASE("alignment pose: centred, along the direction vector, sensors along the travel", "[stairmode]") {
  const double yaw = 0.8;
  const StairModel m = DefaultFlight(yaw, Eigen::Vector3d(1.0, 2.0, 0.5));
  const Eigen::Vector2d dir(std::cos(yaw), std::sin(yaw)), left(-dir.y(), dir.x());
  SECTION("up, facing forward: before the lowest edge, facing up the stairs") {
    const AlignmentPose p = ComputeAlignmentPose(m, TravelDirection::kUp, Facing::kForward, 0.4);
    CHECK(std::abs(std::remainder(p.yaw - yaw, 2.0 * M_PI)) < 1e-12);
    CHECK((p.position.head<2>() - m.center).dot(left) == Approx(0.0).margin(1e-12));
    CHECK((p.position.head<2>() - m.center).dot(dir) == Approx(-0.4));
    CHECK(p.position.z() == Approx(0.5));
    CHECK(p.sensor_direction.head<2>().normalized().dot(dir) == Approx(1.0));
    CHECK(p.sensor_direction.z() == Approx(0.17 / std::hypot(0.17, 0.27)));
  }
  SECTION("down, facing backward (seed 001 [0042]): at the top, turned round, sensors down the stairs") {
    const AlignmentPose p = ComputeAlignmentPose(m, TravelDirection::kDown, Facing::kBackward, 0.4);
    CHECK(std::abs(std::remainder(p.yaw - yaw, 2.0 * M_PI)) < 1e-12);  // facing up while going down
    CHECK((p.position.head<2>() - m.center).dot(dir) == Approx(m.edge_offsets.back() + 0.4));
    CHECK((p.position.head<2>() - m.center).dot(left) == Approx(0.0).margin(1e-12));
    CHECK(p.position.z() == Approx(0.5 + 7 * 0.17));
    CHECK(p.sensor_direction.head<2>().normalized().dot(dir) == Approx(-1.0));
    CHECK(p.sensor_direction.z() < 0.0);
  }
  CHECK_THROWS_AS(ComputeAlignmentPose(StairModel{}, TravelDirection::kUp, Facing::kForward), std::invalid_argument);
}

TEST_CASE("stair mode on stairs found from footfalls: the loop's flights and their poses", "[stairmode]") {
  const auto route = stairplan::testing::TwoUpTwoDownLoop();
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  std::vector<StairModel> models;
  for (const auto& s : StairsFromFootfalls(WalkFootfalls(route, walk))) models.push_back(s.model);
  REQUIRE(models.size() == 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const StairModel truth = route[i].Model();
    const TravelDirection travel = route[i].stairs.direction();
    const AlignmentPose found = ComputeAlignmentPose(models[i], travel, Facing::kForward);
    const AlignmentPose exact = ComputeAlignmentPose(truth, travel, Facing::kForward);
    INFO("flight " << i);
    CHECK(std::abs(std::remainder(found.yaw - exact.yaw, 2.0 * M_PI)) < 2.0 * M_PI / 180.0);
    CHECK((found.position - exact.position).norm() < 0.05);
    // Standing at the alignment pose engages the mode for that flight.
    StairMode fresh(models);
    CHECK(fresh.Update(found.position.head<2>()) == static_cast<int>(i));
  }
}
