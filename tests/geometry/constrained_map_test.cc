// ConstrainedMap v1: step regions inside treads with their margins, collision regions covering
// the rest, direction and facing awareness.
#include <catch2/catch.hpp>

#include <random>

#include "stairplan/geometry/constrained_map.h"

using namespace stairplan;

namespace {

double XMin(const Polygon2& p) {
  double v = 1e9;
  for (const auto& q : p.vertices) v = std::min(v, q.x());
  return v;
}
double XMax(const Polygon2& p) {
  double v = -1e9;
  for (const auto& q : p.vertices) v = std::max(v, q.x());
  return v;
}

}  // namespace

TEST_CASE("ascending: step regions keep the edge and riser margins", "[map]") {
  const Staircase stairs(StairSpec{});
  ConstrainedMapSettings m;
  const auto map = ConstrainedMap::FromStaircase(stairs, Facing::kForward, m);
  REQUIRE(map.size() == stairs.surface_count());
  for (int k = 1; k < stairs.steps(); ++k) {
    const auto& s = stairs.surface(k);
    const auto& r = map.stair(k).step_region;
    REQUIRE_FALSE(r.empty());
    CHECK(XMin(r) == Approx(s.x_begin + m.edge_margin));
    CHECK(XMax(r) == Approx(s.x_end - m.riser_margin));
    CHECK(r.z == Approx(s.z));
  }
}

TEST_CASE("descending: the riser margin is at the start of each tread", "[map]") {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  ConstrainedMapSettings m;
  const auto map = ConstrainedMap::FromStaircase(stairs, Facing::kForward, m);
  const auto& s = stairs.surface(3);
  CHECK(XMin(map.stair(3).step_region) == Approx(s.x_begin + m.riser_margin));
  CHECK(XMax(map.stair(3).step_region) == Approx(s.x_end - m.edge_margin));
}

TEST_CASE("descending backwards uses the middle of the tread", "[map]") {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  ConstrainedMapSettings m;
  m.backward_middle_fraction = 0.6;
  const auto map = ConstrainedMap::FromStaircase(stairs, Facing::kBackward, m);
  const auto& s = stairs.surface(2);
  const double depth = XMax(map.stair(2).step_region) - XMin(map.stair(2).step_region);
  CHECK(depth == Approx(0.6 * (s.x_end - s.x_begin)));
  CHECK(0.5 * (XMin(map.stair(2).step_region) + XMax(map.stair(2).step_region)) == Approx(0.5 * (s.x_begin + s.x_end)));
}

TEST_CASE("every surface point is in the step region or in a collision region, never both", "[map]") {
  std::mt19937 rng(11);
  for (auto dir : {TravelDirection::kUp, TravelDirection::kDown}) {
    for (auto facing : {Facing::kForward, Facing::kBackward}) {
      StairSpec spec;
      spec.direction = dir;
      const Staircase stairs(spec);
      const auto map = ConstrainedMap::FromStaircase(stairs, facing);
      std::uniform_real_distribution<double> ux(stairs.x_min(), stairs.x_max()), uy(-0.5, 0.5);
      for (int i = 0; i < 3000; ++i) {
        const Eigen::Vector2d p(ux(rng), uy(rng));
        const int k = map.StairAt(p);
        if (k < 0) continue;  // exactly on a boundary
        const bool step = map.InStepRegion(k, p, 0.0);
        const bool collide = map.InCollisionRegion(k, p);
        CHECK((step || collide));
        if (step && collide) {
          // Only shared boundaries may be in both.
          CHECK(map.stair(k).step_region.SignedDistance(p) > -1e-9);
        }
      }
    }
  }
}

TEST_CASE("shallow treads get no step region and are wholly collision", "[map]") {
  StairSpec spec;
  spec.run = 0.14;
  spec.nosing = 0.02;
  const Staircase stairs(spec);
  const auto map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  CHECK(map.stair(2).step_region.empty());
  CHECK(map.InCollisionRegion(2, {0.5 * (stairs.surface(2).x_begin + stairs.surface(2).x_end), 0.0}));
  CHECK_FALSE(map.stair(0).step_region.empty());
}

TEST_CASE("a robot collision band trims the step region and stays convex", "[map]") {
  const Staircase stairs(StairSpec{});
  auto map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const double lo = XMin(map.stair(3).step_region), hi = XMax(map.stair(3).step_region);
  map.AddCollisionBand(3, hi - 0.03, hi + 0.1, RegionKind::kRobot);
  CHECK(XMax(map.stair(3).step_region) == Approx(hi - 0.03));
  CHECK(XMin(map.stair(3).step_region) == Approx(lo));
  CHECK(map.InCollisionRegion(3, {hi - 0.01, 0.0}));
  CHECK(map.stair(3).step_region.Area() > 0.0);
}

TEST_CASE("bad margins are rejected", "[map]") {
  const Staircase stairs(StairSpec{});
  ConstrainedMapSettings m;
  m.edge_margin = -0.1;
  CHECK_THROWS_AS(ConstrainedMap::FromStaircase(stairs, Facing::kForward, m), std::invalid_argument);
}

TEST_CASE("the convex hull of random points contains them all and is counter-clockwise", "[map][hull]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector2d> points;
    const int n = 3 + trial % 6;
    for (int i = 0; i < n; ++i) {
      const double x = coordinate(rng);
      const double y = coordinate(rng);
      points.emplace_back(x, y);
    }
    const Polygon2 hull = ConvexHull(points);
    REQUIRE(hull.vertices.size() >= 3);
    REQUIRE(hull.vertices.size() <= points.size());
    for (const Eigen::Vector2d& p : points) CHECK(hull.Contains(p, 1e-12));
    CHECK(hull.Area() > 0.0);  // counter-clockwise
  }
  // A square with a point inside: the inside point is dropped.
  const Polygon2 square = ConvexHull({{0, 0}, {1, 0}, {0.5, 0.5}, {1, 1}, {0, 1}});
  CHECK(square.vertices.size() == 4);
  CHECK(square.Area() == Approx(1.0));
  CHECK(ConvexHull({{0, 0}, {1, 1}}).empty());
}
