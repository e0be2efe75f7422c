// Stairs from footfalls (seed 001) on the synthetic loop of [0047], on hand-made footfalls that
// exercise the pair rules, and the footfall CSV reader's errors.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/footfall_stairs.h"
#include "perception/footfall_scenes.h"

using namespace stairplan;

namespace {

double AngleDeg(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

// Distance along the true direction between a found edge point and the true edge k.
double EdgeError(const StairModel& truth, int k, const Eigen::Vector2d& point) {
  const auto edges = truth.Edges();
  const Eigen::Vector2d mid = 0.5 * (edges[static_cast<std::size_t>(k)].a + edges[static_cast<std::size_t>(k)].b).head<2>();
  return std::abs((point - mid).dot(truth.direction));
}

Footfall At(double t, double x, double y, double z) {
  Footfall f;
  f.t = t;
  f.leg = "LF";
  f.position = Eigen::Vector3d(x, y, z);
  return f;
}

}  // namespace

TEST_CASE("footfalls: a loop up two flights and down two gives the four staircases", "[footfalls]") {
  const auto route = stairplan::testing::TwoUpTwoDownLoop();
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  walk.seed = 1;
  const auto footfalls = WalkFootfalls(route, walk);
  const auto found = StairsFromFootfalls(footfalls);
  REQUIRE(found.size() == 4u);
  const TravelDirection expected[4] = {TravelDirection::kUp, TravelDirection::kUp, TravelDirection::kDown, TravelDirection::kDown};
  for (std::size_t i = 0; i < 4; ++i) {
    const StairModel truth = route[i].Model();
    const FootfallStaircase& s = found[i];
    INFO("flight " << i);
    REQUIRE(s.model.steps == truth.steps);
    CHECK(s.traversal == expected[i]);
    CHECK(AngleDeg(s.model.direction, truth.direction) <= 2.0);
    CHECK(std::abs(s.model.rise - truth.rise) <= 0.01);
    CHECK(std::abs(s.model.run - truth.run) <= 0.02);
    for (int k = 0; k <= truth.steps; ++k) {
      CHECK(std::abs(s.model.levels[static_cast<std::size_t>(k)] - truth.levels[static_cast<std::size_t>(k)]) <= 0.01);
      // A tread's own mean of four footfalls with 1 cm noise: within three of its sigmas.
      CHECK(std::abs(s.tread_heights[static_cast<std::size_t>(k)] - truth.levels[static_cast<std::size_t>(k)]) <= 0.015);
    }
    const auto edges = s.model.Edges();
    for (int k = 0; k < truth.steps; ++k) {
      CHECK(EdgeError(truth, k, 0.5 * (edges[static_cast<std::size_t>(k)].a + edges[static_cast<std::size_t>(k)].b).head<2>()) <= 0.02);
      CHECK(EdgeError(truth, k, s.edges[static_cast<std::size_t>(k)].midpoint.head<2>()) <= 0.03);
      // Every edge line is perpendicular to the direction.
      CHECK(std::abs(s.edges[static_cast<std::size_t>(k)].along.dot(s.model.direction)) < 1e-12);
    }
  }
}

TEST_CASE("footfalls: twenty noisy loops all give four staircases of the right size", "[footfalls]") {
  const auto route = stairplan::testing::TwoUpTwoDownLoop();
  for (std::uint32_t seed = 2; seed < 22; ++seed) {
    FootfallWalkSettings walk;
    walk.sigma = 0.01;
    walk.seed = seed;
    const auto found = StairsFromFootfalls(WalkFootfalls(route, walk));
    INFO("seed " << seed);
    REQUIRE(found.size() == 4u);
    for (std::size_t i = 0; i < 4; ++i) {
      const StairModel truth = route[i].Model();
      CHECK(found[i].model.steps == truth.steps);
      CHECK(AngleDeg(found[i].model.direction, truth.direction) <= 2.0);
      for (int k = 0; k <= truth.steps; ++k) {
        CHECK(std::abs(found[i].model.levels[static_cast<std::size_t>(k)] - truth.levels[static_cast<std::size_t>(k)]) <= 0.015);
      }
    }
  }
}

TEST_CASE("footfalls: flat walking and a single step are not stairs", "[footfalls]") {
  std::vector<Footfall> flat, kerb;
  for (int i = 0; i < 30; ++i) {
    flat.push_back(At(i, 0.3 * i, (i % 2) ? 0.15 : -0.15, 0.0));
    kerb.push_back(At(i, 0.3 * i, (i % 2) ? 0.15 : -0.15, i < 15 ? 0.0 : 0.17));
  }
  CHECK(StairsFromFootfalls(flat).empty());
  CHECK(StairsFromFootfalls(kerb).empty());  // one riser: fewer than min_risers
}

TEST_CASE("footfalls: an intervening footfall breaks a pair (a ramp in short steps)", "[footfalls]") {
  // Two feet walking up a ramp in short steps: 0.06 m up per step is below the riser threshold,
  // two steps (0.12 m over 0.3 m) would pass it, but the step between them intervenes.
  std::vector<Footfall> f;
  for (int i = 0; i < 12; ++i) {
    f.push_back(At(i, 0.15 * i, 0.0, 0.06 * i));
    f.push_back(At(i + 0.5, 0.15 * i, 0.3, 0.06 * i));
  }
  CHECK(StairsFromFootfalls(f).empty());
  FootfallStairsSettings blind;
  blind.corridor = 0.0;  // nothing ever intervenes: the two-step pairs make a false staircase
  CHECK_FALSE(StairsFromFootfalls(f, blind).empty());
}

TEST_CASE("footfalls: hand-placed footfalls give exact treads and edges", "[footfalls]") {
  std::vector<Footfall> f;
  for (int k = 0; k < 5; ++k) {
    for (double y : {-0.15, 0.15}) f.push_back(At(k + (y > 0 ? 0.5 : 0.0), 0.28 * k, y, 0.17 * k));
  }
  const auto found = StairsFromFootfalls(f);
  REQUIRE(found.size() == 1u);
  CHECK(found[0].model.steps == 4);
  CHECK(found[0].model.rise == Approx(0.17));
  CHECK(found[0].model.run == Approx(0.28));
  CHECK(AngleDeg(found[0].model.direction, Eigen::Vector2d::UnitX()) < 1e-6);
  CHECK(found[0].traversal == TravelDirection::kUp);
  for (int k = 0; k < 4; ++k) CHECK(found[0].edges[static_cast<std::size_t>(k)].midpoint.x() == Approx(0.14 + 0.28 * k));
  CHECK(found[0].model.center.y() == Approx(0.0).margin(1e-12));
}

TEST_CASE("footfall CSV: round trip and errors naming the file and line", "[footfalls][errors]") {
  const auto footfalls = WalkFootfalls(stairplan::testing::TwoUpTwoDownLoop());
  const auto back = ParseFootfallCsv(FootfallCsv(footfalls), "mem");
  REQUIRE(back.size() == footfalls.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    REQUIRE(back[i].leg == footfalls[i].leg);
    REQUIRE((back[i].position - footfalls[i].position).norm() < 1e-6);
  }
  const auto error = [](const std::string& text) {
    try {
      ParseFootfallCsv(text, "walk.csv");
    } catch (const FieldError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(error("t,leg,x,y,z\n0,LF,0,0,0\n1,RF,0,zero,0\n"), Catch::Contains("walk.csv: line 3"));
  CHECK_THAT(error("t,leg,x,y,z\n0,LF,0,0\n"), Catch::Contains("walk.csv: line 2"));
  CHECK_THAT(error("t,leg,x,y,z\n\n# comment\n0,LF,0,nan,0\n"), Catch::Contains("walk.csv: line 4"));
  CHECK_THAT(error("time,foot,x,y,z\n"), Catch::Contains("walk.csv: line 1"));
  CHECK_THAT(error(""), Catch::Contains("walk.csv: line 1"));
  CHECK_THAT(error("t,leg,x,y,z\n0,,0,0,0\n"), Catch::Contains("walk.csv: line 2"));
}
