// Where stair mode engages (seed 001 [0043], claim 7): at one tracked pose, and along the track a
// footfall log gives the robot (the planner's --footfalls path); the stairs' frame in the world.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/perception/footfall_track.h"
#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/stair_mode_engagement.h"
#include "perception/footfall_scenes.h"

using namespace stairplan;

namespace {

// The default flight ascending along `yaw` from `origin`, as the footfalls or a cloud place one.
StairModel YawedFlight(double yaw, const Eigen::Vector3d& origin) { return ModelOfStaircase(Staircase(StairSpec{}), origin, yaw); }

GroundPose PoseAt(const Eigen::Vector2d& xy, double yaw = 0.0) {
  GroundPose p;
  p.xy = xy;
  p.yaw = yaw;
  return p;
}

}  // namespace

TEST_CASE("stair mode at a tracked pose: off beyond the engage distance, on within it", "[stairmode]") {
  const double yaw = 0.6;
  const StairModel m = YawedFlight(yaw, Eigen::Vector3d(3.0, -2.0, 0.4));
  const Eigen::Vector2d dir(std::cos(yaw), std::sin(yaw)), left(-dir.y(), dir.x());
  StairModeSettings settings;  // engages within 1 m
  for (const double d : {0.2, 0.99, 1.01, 2.5}) {
    INFO("distance " << d);
    // Before the lowest edge on the centre line, turned any way; beside the flight; past the top.
    const StairModeEngagement before = StairModeAtPose(m, PoseAt(m.center - d * dir, 2.0));
    CHECK(before.engaged == (d <= 1.0));
    CHECK(before.distance == Approx(d));
    CHECK(before.engage_distance == 1.0);
    CHECK(before.pose.yaw == 2.0);
    const Eigen::Vector2d side = m.center + 0.5 * m.edge_offsets.back() * dir + (0.5 * m.width + d) * left;
    CHECK(StairModeAtPose(m, PoseAt(side)).engaged == (d <= 1.0));
    CHECK(StairModeAtPose(m, PoseAt(m.center + (m.edge_offsets.back() + d) * dir)).engaged == (d <= 1.0));
  }
  settings.engage_distance = 0.5;
  CHECK_FALSE(StairModeAtPose(m, PoseAt(m.center - 0.6 * dir), settings).engaged);
  CHECK(StairModeAtPose(m, PoseAt(m.center - 0.4 * dir), settings).engaged);
  settings.engage_distance = -1.0;
  CHECK_THROWS_WITH(StairModeAtPose(m, PoseAt(m.center), settings), Catch::Contains("engage_distance"));
}

TEST_CASE("footfall track: the body over its feet, heading the way it walks, stair mode engaging before each flight", "[stairmode][footfalls]") {
  const auto route = stairplan::testing::TwoUpTwoDownLoop();
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  const std::vector<Footfall> footfalls = WalkFootfalls(route, walk);
  const std::vector<FootfallStaircase> found = StairsFromFootfalls(footfalls);
  REQUIRE(found.size() == 4u);
  std::vector<StairModel> models;
  for (const FootfallStaircase& s : found) models.push_back(s.model);
  const std::vector<GroundPose> track = TrackFromFootfalls(footfalls);
  REQUIRE(!track.empty());
  REQUIRE(track.size() < footfalls.size());  // poses begin once all four feet are down
  for (std::size_t i = 1; i < track.size(); ++i) REQUIRE(track[i].t >= track[i - 1].t);
  for (std::size_t i = 0; i < 4; ++i) {
    INFO("flight " << i);
    const StairModeEngagement e = EngagementAlongTrack(track, models, static_cast<int>(i));
    REQUIRE(e.engaged);
    CHECK(e.distance <= 1.0);
    // In stair mode for the flight before its first footfall on it; on the flight, once the hind
    // feet are on it too (they land in the front feet's footholds 2.5 periods later), headed up
    // or down it as the loop walks it.
    CHECK(e.pose.t < found[i].t_begin);
    int on_flight = 0;
    for (const GroundPose& p : track) {
      if (p.t < found[i].t_begin + 2.5 * walk.step_period || p.t > found[i].t_end) continue;
      ++on_flight;
      CHECK(std::abs(std::remainder(p.yaw - route[i].yaw, 2.0 * M_PI)) < 0.15);
    }
    CHECK(on_flight >= 4);
    // The pose before it was out of range (or in stair mode for the flight before); the loop
    // starts before the first flight, in range from its first pose.
    const auto at = std::find_if(track.begin(), track.end(), [&](const GroundPose& p) { return p.t == e.pose.t; });
    REQUIRE(at != track.end());
    if (at == track.begin()) {
      CHECK(i == 0);
      continue;
    }
    const bool previous_out = DistanceToFlight(models[i], (at - 1)->xy) > 1.0;
    const bool previous_elsewhere = i > 0 && DistanceToFlight(models[i - 1], (at - 1)->xy) <= 1.5;
    CHECK((previous_out || previous_elsewhere));
  }
  CHECK_THROWS_AS(EngagementAlongTrack(track, models, 4), std::invalid_argument);
  // Never near: not engaged, at the track's nearest pose.
  const StairModel far = YawedFlight(0.0, Eigen::Vector3d(100.0, 100.0, 0.0));
  const StairModeEngagement none = EngagementAlongTrack(track, {far}, 0);
  CHECK_FALSE(none.engaged);
  CHECK(none.distance > 90.0);
  for (const GroundPose& p : track) CHECK(DistanceToFlight(far, p.xy) >= none.distance);
}

TEST_CASE("footfall track without front and hind leg names: headed along its path", "[stairmode][footfalls]") {
  std::vector<Footfall> footfalls;
  // Two feet, A and B, stepping along +y.
  for (int k = 0; k < 6; ++k) {
    Footfall f;
    f.t = 0.5 * k;
    f.leg = k % 2 == 0 ? "A" : "B";
    f.position << (k % 2 == 0 ? 0.15 : -0.15), 0.3 * k, 0.0;
    footfalls.push_back(f);
  }
  const std::vector<GroundPose> track = TrackFromFootfalls(footfalls);
  REQUIRE(track.size() == 5u);
  for (const GroundPose& p : track) CHECK(p.yaw == Approx(M_PI / 2));
  CHECK(track.front().xy.x() == Approx(0.0).margin(1e-12));
  CHECK(TrackFromFootfalls({}).empty());
}

TEST_CASE("stair frame: a plan's poses in the world and back", "[stairmode]") {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  const StairFrame frame{ModelOfStaircase(stairs, Eigen::Vector3d(1.0, 2.0, 0.0), 2.5), TravelDirection::kDown, spec.nosing};
  const GroundPose p = PoseAt(Eigen::Vector2d(-0.4, 0.1), 0.3);
  const GroundPose w = frame.ToWorld(p);
  // The plan frame's origin is the first riser met going down: the top edge, the nosing behind it.
  const Eigen::Vector3d origin_W = frame.model.StairToWorld(Eigen::Vector3d::Zero(), TravelDirection::kDown, spec.nosing);
  const double travel_yaw = frame.model.TravelYaw(TravelDirection::kDown);
  CHECK(std::abs(std::remainder(travel_yaw - 2.5, 2.0 * M_PI)) < 1e-12);
  CHECK((w.xy - origin_W.head<2>()).norm() == Approx(std::hypot(0.4, 0.1)));
  CHECK(std::abs(std::remainder(w.yaw - 0.3 - 2.5, 2.0 * M_PI)) < 1e-12);
  const GroundPose back = frame.ToStair(w);
  CHECK((back.xy - p.xy).norm() < 1e-12);
  CHECK(back.yaw == Approx(0.3));
}
