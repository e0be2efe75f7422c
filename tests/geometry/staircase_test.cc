// Staircase: resolved geometry, queries, and rejection of nonsense.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/staircase.h"

using stairplan::FieldError;
using stairplan::Staircase;
using stairplan::StairSpec;
using stairplan::TravelDirection;

TEST_CASE("ascending staircase surfaces follow rise and run", "[staircase]") {
  const Staircase stairs(StairSpec{});
  REQUIRE(stairs.surface_count() == 8);
  CHECK(stairs.total_rise() == Approx(7 * 0.17));
  for (int k = 1; k < 7; ++k) {
    const auto& s = stairs.surface(k);
    CHECK(s.z == Approx(0.17 * k));
    CHECK(s.x_end - s.x_begin == Approx(0.27));  // nosing to nosing
    CHECK(stairs.HeightAt(0.5 * (s.x_begin + s.x_end), 0.0) == Approx(s.z));
    CHECK(stairs.SurfaceIndexAt(0.5 * (s.x_begin + s.x_end), 0.3) == k);
  }
  CHECK(stairs.edges().front().x_nose == Approx(-0.02));
  CHECK(std::isnan(stairs.HeightAt(0.1, 0.6)));  // beyond the 1 m width
  CHECK(std::isnan(stairs.HeightAt(stairs.x_max() + 0.1, 0.0)));
}

TEST_CASE("descending staircase falls along x and its nosings overhang forward", "[staircase]") {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  CHECK(stairs.surface(0).z == Approx(7 * 0.17));
  CHECK(stairs.surface(7).z == Approx(0.0).margin(1e-12));
  CHECK(stairs.edges().front().x_nose == Approx(0.02));
  CHECK(stairs.HeightAt(0.01, 0.0) == Approx(7 * 0.17));  // still on the top landing's lip
  CHECK(stairs.HeightAt(0.03, 0.0) == Approx(6 * 0.17));
}

TEST_CASE("per-step rises and runs are honoured", "[staircase]") {
  StairSpec spec;
  spec.steps = 3;
  spec.rises = {0.15, 0.18, 0.16};
  spec.runs = {0.25, 0.30};
  const Staircase stairs(spec);
  CHECK(stairs.surface(2).z == Approx(0.33));
  CHECK(stairs.surface(2).x_end - stairs.surface(2).x_begin == Approx(0.30));
  CHECK(stairs.total_rise() == Approx(0.49));
}

TEST_CASE("solids: blocks under surfaces and nosing lips at edges", "[staircase]") {
  const Staircase stairs(StairSpec{});
  const auto solids = stairs.Solids();
  int blocks = 0, lips = 0;
  for (const auto& box : solids) {
    CHECK((box.max.array() > box.min.array()).all());
    (box.kind == stairplan::SolidKind::kBlock ? blocks : lips)++;
  }
  CHECK(blocks == 8);
  CHECK(lips == 7);
  // A point just above every tread centre is outside all solids; just below it is inside one.
  for (int k = 0; k < stairs.surface_count(); ++k) {
    const auto& s = stairs.surface(k);
    const Eigen::Vector3d above(0.5 * (s.x_begin + s.x_end), 0.0, s.z + 1e-3);
    const Eigen::Vector3d below(above.x(), 0.0, s.z - 1e-3);
    double min_above = 1e9, min_below = 1e9;
    for (const auto& box : solids) {
      min_above = std::min(min_above, box.SignedDistance(above));
      min_below = std::min(min_below, box.SignedDistance(below));
    }
    CHECK(min_above == Approx(1e-3).margin(1e-9));
    CHECK(min_below < 0.0);
  }
}

TEST_CASE("surface index is consistent with heights over random points", "[staircase]") {
  std::mt19937 rng(7);
  StairSpec spec;
  spec.steps = 5;
  const Staircase stairs(spec);
  std::uniform_real_distribution<double> ux(stairs.x_min(), stairs.x_max()), uy(-0.5, 0.5);
  for (int i = 0; i < 2000; ++i) {
    const double x = ux(rng), y = uy(rng);
    const int k = stairs.SurfaceIndexAt(x, y);
    REQUIRE(k >= 0);
    const auto& s = stairs.surface(k);
    CHECK(x >= s.x_begin - 1e-12);
    CHECK(x <= s.x_end + 1e-12);
    CHECK(stairs.HeightAt(x, y) == s.z);
  }
}

TEST_CASE("nonsense stairs are rejected with the field named", "[staircase]") {
  const auto field_of = [](StairSpec spec) {
    try {
      Staircase stairs(spec);
    } catch (const FieldError& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  StairSpec s;
  s.rise = -0.1;
  CHECK(field_of(s) == "rise");
  s = {};
  s.run = 0.0;
  CHECK(field_of(s) == "run");
  s = {};
  s.run = std::nan("");
  CHECK(field_of(s) == "run");
  s = {};
  s.steps = 0;
  CHECK(field_of(s) == "steps");
  s = {};
  s.nosing = 0.2;
  CHECK(field_of(s) == "nosing");
  s = {};
  s.rises = {0.1, 0.2};
  CHECK(field_of(s) == "rises");
  s = {};
  s.runs = std::vector<double>(6, 0.27);
  s.runs[3] = -1.0;
  CHECK(field_of(s) == "runs[3]");
  s = {};
  s.width = 1e9;
  CHECK(field_of(s) == "width");
}
