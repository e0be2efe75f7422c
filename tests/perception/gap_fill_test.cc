// Gap filling per seed 000 [0042] on constructed maps: a hole behind a near-far contrast is an
// occlusion filled flat at the far (low) surface; a hole without contrast is filled smoothly;
// measured cells never change.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "stairplan/perception/gap_fill.h"
#include "perception/perception_scenes.h"

using namespace stairplan;

namespace {

constexpr double kRes = 0.02;

// A map along x (profile) of nx cells by ny rows, filled by a function of the cell centre; the
// function returns NaN for cells with no data.
template <typename Fn>
HeightMap MakeMap(int nx, int ny, Fn height) {
  HeightMap map(Eigen::Vector2d::Zero(), kRes, nx, ny);
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      const double h = height(c.x(), c.y());
      if (!std::isnan(h)) map.Set(ix, iy, static_cast<float>(h), CellState::kMeasured);
    }
  }
  return map;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST_CASE("looking down: the tread hidden behind a nosing is filled flat at the tread", "[gapfill]") {
  // Upper tread (0.17) up to its nosing at x = 0.3, then the lower tread (0.0) seen from 0.5 on.
  HeightMap map = MakeMap(40, 10, [](double x, double) { return x < 0.3 ? 0.17 : (x < 0.5 ? kNaN : 0.0); });
  const GapFillReport report = FillGaps(map);
  CHECK(report.occluded == 10 * 10);
  CHECK(report.smoothed == 0);
  for (int iy = 0; iy < 10; ++iy) {
    for (int ix = 15; ix < 25; ++ix) {
      REQUIRE(map.state(ix, iy) == CellState::kOccluded);
      REQUIRE(map.height(ix, iy) == Approx(0.0).margin(1e-6));
    }
  }
}

TEST_CASE("looking up: a tread seen only as its risers' tops is filled flat at its own height", "[gapfill]") {
  // Riser tops at x = 0.2 (0.34) and x = 0.48 (0.51); the tread between them was never seen.
  HeightMap map = MakeMap(30, 8, [](double x, double) {
    if (x < 0.04) return 0.17;
    if (std::abs(x - 0.21) < 0.011) return 0.34;
    if (std::abs(x - 0.49) < 0.011) return 0.51;
    return kNaN;
  });
  FillGaps(map);
  for (int iy = 0; iy < 8; ++iy) {
    for (int ix = 11; ix < 24; ++ix) {
      REQUIRE(map.state(ix, iy) == CellState::kOccluded);
      REQUIRE(map.height(ix, iy) == Approx(0.34).margin(1e-6));
    }
  }
}

TEST_CASE("a hole in a slope without contrast is filled smoothly and exactly for a plane", "[gapfill]") {
  const auto plane = [](double x, double y) { return 0.3 + 0.1 * x - 0.05 * y; };
  HeightMap map = MakeMap(50, 50, [&](double x, double y) {
    return std::hypot(x - 0.5, y - 0.5) < 0.1 ? kNaN : plane(x, y);
  });
  const int holes = map.CountState(CellState::kUnknown);
  const GapFillReport report = FillGaps(map);
  CHECK(report.occluded == 0);
  CHECK(report.smoothed == holes);
  CHECK(report.unknown == 0);
  for (int iy = 0; iy < 50; ++iy) {
    for (int ix = 0; ix < 50; ++ix) {
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      REQUIRE(map.height(ix, iy) == Approx(plane(c.x(), c.y())).margin(1e-4));
    }
  }
}

TEST_CASE("wide holes are marked poor and holes with no far side stay unknown", "[gapfill]") {
  HeightMap map = MakeMap(60, 60, [](double x, double y) {
    if (x > 1.0) return kNaN;  // beyond the data: nothing to bridge to
    return std::hypot(x - 0.5, y - 0.6) < 0.3 ? kNaN : 0.2;
  });
  const GapFillReport report = FillGaps(map);
  CHECK(report.poor > 0);
  int ix = 0, iy = 0;
  REQUIRE(map.CellOf(Eigen::Vector2d(0.5, 0.6), &ix, &iy));
  CHECK(map.state(ix, iy) == CellState::kPoor);
  CHECK(map.height(ix, iy) == Approx(0.2).margin(1e-4));
  REQUIRE(map.CellOf(Eigen::Vector2d(1.1, 0.6), &ix, &iy));
  CHECK(map.state(ix, iy) == CellState::kUnknown);
  CHECK(std::isnan(map.height(ix, iy)));
}

TEST_CASE("random holes: measured cells never change and fills stay within the data", "[gapfill]") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double a = unit(rng), b = unit(rng), step_x = 0.2 + unit(rng) * 0.4;
    const bool stepped = trial % 2 == 0;
    const auto surface = [&](double x, double y) {
      return stepped ? (x < step_x ? 0.0 : 0.18) : 0.1 * std::sin(3.0 * x + a) + 0.05 * std::cos(4.0 * y + b);
    };
    HeightMap map = MakeMap(40, 40, [&](double x, double y) { return unit(rng) < 0.25 ? kNaN : surface(x, y); });
    const HeightMap before = map;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int iy = 0; iy < 40; ++iy) {
      for (int ix = 0; ix < 40; ++ix) {
        if (before.state(ix, iy) != CellState::kMeasured) continue;
        lo = std::min(lo, before.height(ix, iy));
        hi = std::max(hi, before.height(ix, iy));
      }
    }
    FillGaps(map);
    for (int iy = 0; iy < 40; ++iy) {
      for (int ix = 0; ix < 40; ++ix) {
        if (before.state(ix, iy) == CellState::kMeasured) {
          REQUIRE(map.state(ix, iy) == CellState::kMeasured);
          REQUIRE(map.height(ix, iy) == before.height(ix, iy));
        } else if (map.state(ix, iy) != CellState::kUnknown) {
          REQUIRE(map.height(ix, iy) >= lo - 1e-6f);
          REQUIRE(map.height(ix, iy) <= hi + 1e-6f);
        }
      }
    }
  }
}

TEST_CASE("on a camera scan of the stairs, filled treads sit at the stairs' heights", "[gapfill]") {
  const Staircase stairs(StairSpec{});
  SensorNoise noise;
  noise.range_sigma = 0.005;
  noise.seed = 8;
  const PointCloud cloud = ScanStairs(stairs, PinholeCamera{}, stairplan::testing::CameraOnBottomLanding(), noise);
  HeightMap map = HeightMap::FromCloud(cloud);
  const GapFillReport report = FillGaps(map);
  CHECK(report.occluded > 100);  // the treads above the camera are only seen as riser tops
  std::vector<double> errors;
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      if (map.state(ix, iy) != CellState::kOccluded) continue;
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      bool near_edge = std::abs(c.y()) > stairs.half_width() - 0.04;
      for (const StairEdge& e : stairs.edges()) near_edge = near_edge || (c.x() > e.x_nose - 0.04 && c.x() < e.x_riser + 0.04);
      if (near_edge || std::isnan(stairs.HeightAt(c.x(), c.y()))) continue;
      errors.push_back(std::abs(map.height(ix, iy) - stairs.HeightAt(c.x(), c.y())));
    }
  }
  REQUIRE(errors.size() > 100u);
  // Where a far nosing's top was missed between two camera rows, its row fills a little low.
  std::sort(errors.begin(), errors.end());
  CHECK(errors[errors.size() / 2] < 0.01);
  CHECK(errors[errors.size() * 9 / 10] < 0.03);
}
