// HeightMap: binning a cloud into float cells with NaN for unknown; a scan of the stairs gives
// the stairs' heights away from the edges.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "stairplan/perception/height_map.h"
#include "perception/perception_scenes.h"

using namespace stairplan;

TEST_CASE("cells take the top of their points and unknown cells are NaN", "[heightmap]") {
  PointCloud cloud;
  cloud.points = {{0.001, 0.001, 0.10}, {0.005, 0.002, 0.30}, {0.009, 0.001, 0.305}, {0.05, 0.001, 0.2}};
  HeightMapSettings settings;
  settings.resolution = 0.01;
  settings.top_band = 0.01;
  const HeightMap map = HeightMap::FromCloud(cloud, settings);
  REQUIRE(map.nx() == 5);
  REQUIRE(map.ny() == 1);
  CHECK(map.height(0, 0) == Approx(0.3025));  // 0.10 is a face below the top, outside the band
  CHECK(map.count(0, 0) == 3);
  CHECK(map.spread(0, 0) == Approx(0.205));
  CHECK(map.state(0, 0) == CellState::kMeasured);
  CHECK(std::isnan(map.height(2, 0)));
  CHECK(map.state(2, 0) == CellState::kUnknown);
  CHECK(map.height(4, 0) == Approx(0.2));
  CHECK(std::isnan(map.HeightAt(10.0, 0.0)));
  CHECK(map.CountState(CellState::kMeasured) == 2);
}

TEST_CASE("cell lookup and cell centres agree", "[heightmap]") {
  const HeightMap map(Eigen::Vector2d(-1.0, 2.0), 0.04, 30, 20);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> ux(-1.0, 0.2), uy(2.0, 2.8);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    int ix = -1, iy = -1;
    REQUIRE(map.CellOf(p, &ix, &iy));
    const Eigen::Vector2d c = map.CellCenter(ix, iy);
    REQUIRE(std::abs(c.x() - p.x()) <= 0.02 + 1e-12);
    REQUIRE(std::abs(c.y() - p.y()) <= 0.02 + 1e-12);
  }
  int ix = 0, iy = 0;
  CHECK_FALSE(map.CellOf(Eigen::Vector2d(-1.01, 2.1), &ix, &iy));
  CHECK_FALSE(map.CellOf(Eigen::Vector2d(0.0, 2.81), &ix, &iy));
}

TEST_CASE("a scan of the stairs maps to the stairs' heights away from the edges", "[heightmap]") {
  const Staircase stairs(StairSpec{});
  const auto scene = stairplan::testing::ScanFromBottom(stairs, 0.0, Eigen::Vector3d::Zero(), 0.005, 3);
  const HeightMap map = HeightMap::FromCloud(scene.cloud);
  int checked = 0;
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      if (map.state(ix, iy) != CellState::kMeasured) continue;
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      // Cells within 4 cm of an edge (nosing, riser, sides) mix surfaces: skip them.
      bool near_edge = std::abs(c.y()) > stairs.half_width() - 0.04;
      for (const StairEdge& e : stairs.edges()) near_edge = near_edge || (c.x() > e.x_nose - 0.04 && c.x() < e.x_riser + 0.04);
      if (near_edge) continue;
      const double truth = stairs.HeightAt(c.x(), c.y());
      if (std::isnan(truth)) continue;
      REQUIRE(map.height(ix, iy) == Approx(truth).margin(0.015));
      ++checked;
    }
  }
  CHECK(checked > 100);
}

TEST_CASE("height map misuse is rejected", "[heightmap]") {
  CHECK_THROWS_AS(HeightMap::FromCloud(PointCloud{}), std::invalid_argument);
  HeightMapSettings settings;
  settings.resolution = 0.0;
  PointCloud one;
  one.points.emplace_back(0, 0, 0);
  CHECK_THROWS_WITH(HeightMap::FromCloud(one, settings), Catch::Contains("resolution"));
  PointCloud huge;
  huge.points = {{0, 0, 0}, {1e5, 1e5, 0}};
  CHECK_THROWS_AS(HeightMap::FromCloud(huge), std::invalid_argument);
}
