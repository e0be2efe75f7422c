// The constrained map from a cloud (acceptance 4): built from a synthetic camera cloud through
// the height map and the tracker, its step regions match the analytic map of the true stairs
// (IoU >= 0.9 per tread, ascending and descending), and data adds collision regions where it
// should (an object on a tread, a badly seen patch).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

#include "stairplan/perception/stair_perception.h"
#include "perception/perception_scenes.h"

using namespace stairplan;

namespace {

struct WorldRegion {
  Polygon2 polygon;                                    // in its own stairs' frame
  std::function<Eigen::Vector2d(const Eigen::Vector2d&)> to_frame;  // world -> that frame
};

// IoU of two regions by sampling the world on a 2.5 mm grid over their joint bounds.
double IoU(const WorldRegion& a, const WorldRegion& b, const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& a_to_world) {
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const auto& v : a.polygon.vertices) {
    const Eigen::Vector2d w = a_to_world(v);
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  lo.array() -= 0.1;
  hi.array() += 0.1;
  long both = 0, either = 0;
  for (double x = lo.x(); x <= hi.x(); x += 0.0025) {
    for (double y = lo.y(); y <= hi.y(); y += 0.0025) {
      const Eigen::Vector2d w(x, y);
      const bool in_a = a.polygon.Contains(a.to_frame(w), 0.0);
      const bool in_b = b.polygon.Contains(b.to_frame(w), 0.0);
      both += (in_a && in_b) ? 1 : 0;
      either += (in_a || in_b) ? 1 : 0;
    }
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

Eigen::Vector2d Rotate(const Eigen::Vector2d& p, double yaw) {
  return Eigen::Vector2d(std::cos(yaw) * p.x() - std::sin(yaw) * p.y(), std::sin(yaw) * p.x() + std::cos(yaw) * p.y());
}

}  // namespace

TEST_CASE("constrained map from a cloud: step regions match the analytic map (IoU >= 0.9)", "[perceptionmap]") {
  const double yaw = 0.6;
  const Eigen::Vector3d offset(1.5, -2.0, 0.3);
  const Staircase truth(StairSpec{});
  SensorNoise noise;
  noise.range_sigma = 0.005;
  noise.seed = 5;
  stairplan::testing::Scene scene;  // the default 160 x 120 camera: treads near eye level are grazed
  scene.cloud = TransformCloud(ScanStairs(truth, PinholeCamera{}, stairplan::testing::CameraOnBottomLanding(), noise), yaw, offset);
  for (const auto& case_ : {std::pair{TravelDirection::kUp, Facing::kForward}, std::pair{TravelDirection::kDown, Facing::kBackward},
                            std::pair{TravelDirection::kDown, Facing::kForward}}) {
    // Named, not a structured binding: C++17 lambdas cannot capture those (clang rejects it).
    const TravelDirection travel = case_.first;
    const Facing facing = case_.second;
    StairPerceptionSettings settings;
    settings.regions.travel = travel;
    settings.regions.facing = facing;
    const StairPerception seen = PerceiveStairs(scene.cloud, settings);
    REQUIRE(seen.fit.found);
    REQUIRE(seen.stairs.has_value());
    const Staircase& fitted = seen.stairs->stairs;
    REQUIRE(fitted.steps() == truth.steps());
    CHECK(fitted.direction() == travel);
    // The truth for this travel: the same flight as a StairSpec walked `travel`, whose frame is
    // the ascending frame flipped about the top riser when descending.
    StairSpec spec = truth.spec();
    spec.direction = travel;
    const Staircase truth_travel(spec);
    const ConstrainedMap expected = ConstrainedMap::FromStaircase(truth_travel, facing);
    const double top_riser = truth.edges().back().x_riser;
    const auto truth_to_frame = [&](const Eigen::Vector2d& w) {
      const Eigen::Vector2d a = Rotate(w - offset.head<2>(), -yaw);  // ascending frame
      return travel == TravelDirection::kUp ? a : Eigen::Vector2d(top_riser - a.x(), -a.y());
    };
    const auto truth_to_world = [&](const Eigen::Vector2d& f) {
      const Eigen::Vector2d a = travel == TravelDirection::kUp ? f : Eigen::Vector2d(top_riser - f.x(), -f.y());
      return Eigen::Vector2d(offset.head<2>() + Rotate(a, yaw));
    };
    const auto fitted_to_frame = [&](const Eigen::Vector2d& w) {
      return Eigen::Vector2d(seen.fit.model.WorldToStair(Eigen::Vector3d(w.x(), w.y(), 0.0), travel, settings.regions.nosing).head<2>());
    };
    for (int k = 1; k < truth.steps(); ++k) {
      INFO("travel " << ToString(travel) << ", facing " << ToString(facing) << ", tread " << k);
      const double iou = IoU({expected.stair(k).step_region, truth_to_frame}, {seen.stairs->map.stair(k).step_region, fitted_to_frame}, truth_to_world);
      CHECK(iou >= 0.9);
      CHECK(seen.stairs->map.stair(k).z == Approx(truth_travel.surface(k).z).margin(0.02));
    }
  }
}

TEST_CASE("constrained map from a cloud: an object on a tread becomes a data collision region", "[perceptionmap]") {
  const Staircase stairs(StairSpec{});
  std::vector<Box3> solids = stairs.Solids();
  Box3 box;  // a 10 cm cube in the middle of tread 2, which the camera sees from above
  const StairSurface& tread = stairs.surface(2);
  const double x_mid = 0.5 * (tread.x_begin + tread.x_end);
  box.min = {x_mid - 0.05, -0.05, tread.z};
  box.max = {x_mid + 0.05, 0.05, tread.z + 0.10};
  solids.push_back(box);
  SensorNoise noise;
  noise.range_sigma = 0.003;
  const PointCloud cloud = ScanSolids(solids, PinholeCamera{}, stairplan::testing::CameraOnBottomLanding(), noise);
  const StairPerception seen = PerceiveStairs(cloud);
  REQUIRE(seen.stairs.has_value());
  const StairRegions& regions = seen.stairs->map.stair(2);
  const bool flagged = std::any_of(regions.collision_regions.begin(), regions.collision_regions.end(), [](const CollisionRegion& r) {
    return r.kind == RegionKind::kData || r.kind == RegionKind::kEdge || r.kind == RegionKind::kRiser;
  });
  CHECK(flagged);
  // No point of the box's footprint may remain in the step region.
  for (double x = box.min.x(); x <= box.max.x(); x += 0.01) {
    for (double y = box.min.y(); y <= box.max.y(); y += 0.01) {
      const Eigen::Vector3d p_S = seen.fit.model.WorldToStair(Eigen::Vector3d(x, y, 0.0), TravelDirection::kUp);
      CHECK_FALSE(seen.stairs->map.InStepRegion(2, p_S.head<2>(), 0.0));
    }
  }
}

TEST_CASE("constrained map from a height map: poor cells become data collision regions", "[perceptionmap]") {
  // A perfect map of the stairs with a wide unseen patch on the bottom landing (no contrast).
  const Staircase stairs(StairSpec{});
  HeightMap map(Eigen::Vector2d(-1.2, -0.5), 0.02, 180, 50);
  const double x_mid = -0.65;
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      if (std::abs(c.x() - x_mid) < 0.15 && std::abs(c.y()) < 0.3) continue;
      const double z = stairs.HeightAt(c.x(), c.y());
      if (!std::isnan(z)) map.Set(ix, iy, static_cast<float>(z), CellState::kMeasured);
    }
  }
  const GapFillReport fill = FillGaps(map);
  REQUIRE(fill.poor > 0);
  const StairModel model = ModelOfStaircase(stairs, Eigen::Vector3d::Zero(), 0.0);
  const PerceivedStairs seen = ConstrainedMapFromHeightMap(map, model);
  CHECK(seen.data_bands > 0);
  const auto& regions = seen.map.stair(0).collision_regions;
  CHECK(std::any_of(regions.begin(), regions.end(), [](const CollisionRegion& r) { return r.kind == RegionKind::kData; }));
  // The model's frame starts at the first walking edge, 2 cm before the riser at x = 0.
  const Eigen::Vector2d hole_S(x_mid - model.center.x(), 0.0);
  CHECK_FALSE(seen.map.InStepRegion(0, hole_S, 0.0));
  // The treads keep their analytic step regions: the data found nothing there.
  const ConstrainedMap analytic = ConstrainedMap::FromStaircase(seen.stairs, Facing::kForward);
  for (int k = 1; k < stairs.steps(); ++k) {
    CHECK(seen.map.stair(k).step_region.Area() == Approx(analytic.stair(k).step_region.Area()).epsilon(1e-9));
  }
}
