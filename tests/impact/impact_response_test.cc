// The impact-response table of seed 000 [0055]-[0068], one test per row.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/planning/impact/impact_response.h"

using namespace stairplan;

namespace {

struct Scene {
  Staircase stairs{StairSpec{}};
  ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);

  // LF swinging to the middle of stair 3's step region; RF standing on stair 3.
  ImpactEvent Event(ImpactKind kind) const {
    const StairSurface& s = stairs.surface(3);
    const double x = 0.5 * (s.x_begin + s.x_end) - 0.01;
    ImpactEvent e;
    e.kind = kind;
    e.leg = "LF";
    e.swing_phase = 0.5;
    e.target_stair = 3;
    e.target_W = {x, 0.18, s.z};
    e.swing_foot_W = {x - 0.1, 0.18, s.z + 0.08};
    e.contralateral_foot_W = {x, -0.18, s.z};
    return e;
  }
};

}  // namespace

TEST_CASE("touchdown classifies the swing leg as stance", "[impact]") {
  const Scene scene;
  const auto r = RespondToImpact(scene.Event(ImpactKind::kTouchdown), scene.map);
  CHECK(r.kind == ResponseKind::kClassifyStance);
  CHECK(r.target_W.isApprox(scene.Event(ImpactKind::kTouchdown).target_W));
}

TEST_CASE("a knee hitting behind the body moves the knee forward", "[impact]") {
  const Scene scene;
  const auto r = RespondToImpact(scene.Event(ImpactKind::kKneeBehindBody), scene.map);
  CHECK(r.kind == ResponseKind::kMoveKneeForward);
  CHECK(r.knee_forward > 0.0);
}

TEST_CASE("striking the contralateral leg shifts the step away inside the step region", "[impact]") {
  const Scene scene;
  ImpactEvent e = scene.Event(ImpactKind::kContralateralStrike);
  e.contralateral_foot_W.y() = 0.12;  // the right foot strayed toward the left leg's target
  ImpactSettings settings;
  const auto r = RespondToImpact(e, scene.map, settings);
  REQUIRE(r.kind == ResponseKind::kAdjustStep);
  CHECK(r.target_W.y() >= e.contralateral_foot_W.y() + settings.contralateral_clearance - 1e-9);
  CHECK(r.target_W.y() > e.target_W.y());  // shifted, not kept
  CHECK(r.target_W.x() == Approx(e.target_W.x()));
  CHECK(scene.map.InStepRegion(3, r.target_W.head<2>()));
  CHECK(r.target_W.z() == Approx(scene.stairs.surface(3).z));
}

TEST_CASE("with no free step region the least risky collision spot is used, never an edge", "[impact]") {
  StairSpec spec;
  spec.run = 0.14;  // too shallow for any step region
  const Staircase stairs(spec);
  const auto map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  REQUIRE(map.stair(2).step_region.empty());
  const StairSurface& s = stairs.surface(2);
  ImpactEvent e;
  e.kind = ImpactKind::kContralateralStrike;
  e.leg = "RF";
  e.target_stair = 2;
  e.target_W = {0.5 * (s.x_begin + s.x_end) - 0.02, -0.18, s.z};
  e.swing_foot_W = e.target_W + Eigen::Vector3d(-0.1, 0.0, 0.05);
  e.contralateral_foot_W = {e.target_W.x(), 0.18, s.z};
  const auto r = RespondToImpact(e, map);
  REQUIRE(r.kind == ResponseKind::kAdjustStepRisky);
  CHECK_THAT(r.reason, Catch::Contains("riser"));
  for (const auto& region : map.stair(2).collision_regions) {
    if (region.kind == RegionKind::kEdge || region.kind == RegionKind::kSide) {
      CHECK(region.polygon.SignedDistance(r.target_W.head<2>()) >= -1e-9);
    }
  }
}

TEST_CASE("crossed legs untangle fore/aft first, then sideways", "[impact]") {
  const Scene scene;
  ImpactSettings settings;
  for (const double ahead : {0.05, -0.05}) {
    ImpactEvent e = scene.Event(ImpactKind::kContralateralCrossing);
    e.swing_foot_W = e.contralateral_foot_W + Eigen::Vector3d(ahead, -0.07, 0.06);  // LF foot past RF
    const auto r = RespondToImpact(e, scene.map, settings);
    REQUIRE(r.kind == ResponseKind::kUntangle);
    REQUIRE(r.waypoints_W.size() == 2);
    const double sign = ahead > 0 ? 1.0 : -1.0;
    CHECK(r.waypoints_W[0].x() == Approx(e.swing_foot_W.x() + sign * settings.untangle_distance));
    CHECK(r.waypoints_W[0].y() == Approx(e.swing_foot_W.y()));  // no sideways motion yet
    CHECK(r.waypoints_W[1].x() == Approx(r.waypoints_W[0].x()));
    CHECK(r.waypoints_W[1].y() == Approx(e.contralateral_foot_W.y() + settings.contralateral_clearance));
    CHECK(scene.map.InStepRegion(3, r.target_W.head<2>()));
  }
}

TEST_CASE("a trip early in swing elevates the foot", "[impact]") {
  const Scene scene;
  ImpactEvent e = scene.Event(ImpactKind::kTrip);
  e.swing_phase = 0.3;
  const auto r = RespondToImpact(e, scene.map);
  CHECK(r.kind == ResponseKind::kElevateFoot);
  CHECK(r.extra_swing_height > 0.0);
}

TEST_CASE("a trip late in swing touches down at once below the foot", "[impact]") {
  const Scene scene;
  ImpactEvent e = scene.Event(ImpactKind::kTrip);
  e.swing_phase = 0.8;
  const auto r = RespondToImpact(e, scene.map);
  REQUIRE(r.kind == ResponseKind::kTouchdownNow);
  CHECK(r.target_W.x() == Approx(e.swing_foot_W.x()));
  CHECK(r.target_W.y() == Approx(e.swing_foot_W.y()));
  CHECK(r.target_W.z() == Approx(scene.stairs.HeightAt(e.swing_foot_W.x(), e.swing_foot_W.y())));
}

TEST_CASE("thigh against body: proceed", "[impact]") {
  const Scene scene;
  CHECK(RespondToImpact(scene.Event(ImpactKind::kThighAgainstBody), scene.map).kind == ResponseKind::kProceed);
}

TEST_CASE("liftoff scuff: proceed", "[impact]") {
  const Scene scene;
  CHECK(RespondToImpact(scene.Event(ImpactKind::kLiftoffScuff), scene.map).kind == ResponseKind::kProceed);
}

TEST_CASE("knee glancing the terrain: proceed", "[impact]") {
  const Scene scene;
  CHECK(RespondToImpact(scene.Event(ImpactKind::kKneeGlancingTerrain), scene.map).kind == ResponseKind::kProceed);
  CHECK(RespondToImpact(scene.Event(ImpactKind::kIpsilateralStrike), scene.map).kind == ResponseKind::kProceed);
}

TEST_CASE("impact responses reject non-finite input", "[impact]") {
  const Scene scene;
  ImpactEvent e = scene.Event(ImpactKind::kTrip);
  e.swing_phase = std::nan("");
  CHECK_THROWS_AS(RespondToImpact(e, scene.map), std::invalid_argument);
  ImpactSettings bad;
  bad.early_swing_phase = 2.0;
  CHECK_THROWS_AS(RespondToImpact(scene.Event(ImpactKind::kTrip), scene.map, bad), std::invalid_argument);
}

TEST_CASE("a foot down outside the step region moves to the region's nearest point, a margin inside", "[impact]") {
  const Scene scene;
  ImpactSettings settings;
  const StairRegions& stair = scene.map.stair(3);
  REQUIRE_FALSE(stair.step_region.empty());
  const double region_end = stair.step_region.XExtent().hi;
  // On the tread past the step region (towards the next riser), at every lateral place inside.
  for (const double y : {-0.2, 0.0, 0.18}) {
    ImpactEvent e = scene.Event(ImpactKind::kMisplacedTouchdown);
    e.swing_phase = 1.0;
    e.swing_foot_W = {region_end + 0.03, y, stair.z};
    REQUIRE_FALSE(scene.map.InStepRegion(3, e.swing_foot_W.head<2>()));
    const auto r = RespondToImpact(e, scene.map, settings);
    INFO("y " << y);
    REQUIRE(r.kind == ResponseKind::kAdjustStep);
    CHECK(scene.map.InStepRegion(3, r.target_W.head<2>()));
    CHECK(stair.step_region.SignedDistance(r.target_W.head<2>()) <= -settings.step_region_margin + 1e-6);
    CHECK((r.target_W.head<2>() - e.swing_foot_W.head<2>()).norm() < 0.03 + 2.0 * settings.step_region_margin);
    CHECK(r.target_W.z() == Approx(stair.z));
  }
  // A target stair the map does not have: nowhere to go.
  ImpactEvent lost = scene.Event(ImpactKind::kMisplacedTouchdown);
  lost.target_stair = scene.map.size();
  CHECK(RespondToImpact(lost, scene.map, settings).kind == ResponseKind::kProceed);
}
