// The nosing uncertainty the fitters write (stairplan/geometry/stair_uncertainty.h) is a property of the
// estimate: on noisy footfalls and camera scans of known stairs, the true nosings lie within it of
// the fitted ones, in the world and relative to the fitted origin where a plan's frame sits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/perception/footfall_walk.h"
#include "stairplan/perception/stair_perception.h"
#include "stairplan/geometry/stair_uncertainty.h"
#include "perception/footfall_scenes.h"
#include "perception/perception_scenes.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

// The largest distance between a fitted nosing and the true one over the flight: in the world,
// and relative to each model's lowest level and first edge (either end), along the true direction.
double NosingError(const StairModel& fit, const StairModel& truth) {
  REQUIRE(fit.steps == truth.steps);
  const Eigen::Vector2d d = truth.direction;
  const auto along = [&](const StairModel& m, int k) { return (m.center + m.edge_offsets[static_cast<std::size_t>(k)] * m.direction).dot(d); };
  const auto level = [&](const StairModel& m, int k) { return m.levels[static_cast<std::size_t>(k + 1)]; };
  double worst = 0.0;
  const int last = truth.steps - 1;
  for (int k = 0; k <= last; ++k) {
    worst = std::max(worst, std::hypot(along(fit, k) - along(truth, k), level(fit, k) - level(truth, k)));
    const double dz = (level(fit, k) - fit.levels.front()) - (level(truth, k) - truth.levels.front());
    for (int first : {0, last}) {
      const double dx = (along(fit, k) - along(fit, first)) - (along(truth, k) - along(truth, first));
      worst = std::max(worst, std::hypot(dx, dz));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("nosing uncertainty: residuals, the samples' own error and the leverage of the far steps", "[perception][uncertainty]") {
  IndexedSamples exact{{0, 1, 2, 3}, {0.0, 0.17, 0.34, 0.51}, 0.0};
  IndexedSamples edges{{1, 2, 3}, {0.0, 0.27, 0.54}, 0.0};
  CHECK(NosingUncertainty(exact, edges, 3) == Approx(0.0).margin(1e-12));
  // Known sample errors alone: twice the standard error of the top level relative to the lowest,
  // 2 * 1 mm * 3 / sqrt(5) (the slope's error over three rises).
  exact.sample_sigma = 0.001;
  const double from_samples = NosingUncertainty(exact, edges, 3);
  CHECK(from_samples == Approx(2.0 * 0.001 * 3.0 / std::sqrt(5.0)));
  CHECK(NosingUncertainty(exact, edges, 3, 1.0) == Approx(0.5 * from_samples));
  // A level 3 mm off: the residuals widen it.
  IndexedSamples off = exact;
  off.value[2] += 0.003;
  const double from_residuals = NosingUncertainty(off, edges, 3);
  CHECK(from_residuals > from_samples);
  // Extrapolating to steps the samples did not reach widens it.
  CHECK(NosingUncertainty(off, edges, 7) > from_residuals);
  CHECK_THROWS_AS(NosingUncertainty(IndexedSamples{{0}, {0.0}, 0.0}, edges, 3), std::invalid_argument);
  CHECK_THROWS_AS(NosingUncertainty(IndexedSamples{{0, 1}, {0.0}, 0.0}, edges, 3), std::invalid_argument);
}

TEST_CASE("nosing uncertainty from footfalls: the true nosings lie within it", "[perception][uncertainty][footfalls]") {
  const auto route = stairplan::testing::TwoUpTwoDownLoop();
  int flights = 0, covered = 0;
  double worst_ratio = 0.0, largest_bound = 0.0;
  const std::uint32_t seeds = stairplan::testing::FullOrSanitized(40u, 10u);
  for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
    FootfallWalkSettings walk;
    walk.sigma = 0.01;
    walk.seed = seed;
    const auto found = StairsFromFootfalls(WalkFootfalls(route, walk));
    REQUIRE(found.size() == route.size());
    for (std::size_t i = 0; i < route.size(); ++i) {
      const double error = NosingError(found[i].model, route[i].Model());
      const double bound = found[i].model.uncertainty;
      INFO("seed " << seed << ", flight " << i << ": error " << error << " m, bound " << bound << " m");
      CHECK(bound > 0.0);
      ++flights;
      covered += error <= bound ? 1 : 0;
      worst_ratio = std::max(worst_ratio, error / bound);
      largest_bound = std::max(largest_bound, bound);
    }
  }
  INFO(covered << " of " << flights << " flights covered; worst error / bound " << worst_ratio << ", largest bound " << largest_bound);
  // About 95 % on each line, the largest over the flight: nine flights in ten at least are
  // covered, none is off by much more, and the bound stays a few centimetres at most.
  CHECK(covered >= flights * 90 / 100);
  CHECK(worst_ratio < 1.6);
  CHECK(largest_bound < 0.05);
}

TEST_CASE("nosing uncertainty from a camera scan: the true nosings lie within it", "[perception][uncertainty]") {
  const Staircase truth(StairSpec{});
  const StairModel true_model = ModelOfStaircase(truth, Eigen::Vector3d::Zero(), 0.0);
  const std::uint32_t seeds = stairplan::testing::FullOrSanitized(6u, 2u);
  for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
    SensorNoise noise;
    noise.range_sigma = 0.005;
    noise.seed = seed;
    const StairPerception seen = PerceiveStairs(ScanStairs(truth, PinholeCamera{}, stairplan::testing::CameraOnBottomLanding(), noise));
    REQUIRE(seen.fit.found);
    const double error = NosingError(seen.fit.model, true_model);
    INFO("seed " << seed << ": error " << error << " m, bound " << seen.fit.model.uncertainty << " m");
    CHECK(error <= seen.fit.model.uncertainty);
    CHECK(seen.fit.model.uncertainty < 0.03);
    // The stairs the map is built on carry it to the planners.
    REQUIRE(seen.stairs.has_value());
    CHECK(seen.stairs->stairs.spec().uncertainty == seen.fit.model.uncertainty);
  }
}
