// The dimensionless design conditions (14)-(16) of the 2012 paper against (11)-(13), and its
// Figure 4(b).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "stairplan/planning/gait/feasibility_figure.h"
#include "stairplan/planning/gait/feasibility_volume.h"
#include "stairplan/planning/gait/gait_design.h"

using namespace stairplan;

TEST_CASE("eqs. (14)-(16) agree with (11)-(13) on 1,000 random designs", "[gait]") {
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int agree = 0;
  int holds14 = 0, holds15 = 0, holds16 = 0, feasible = 0;
  for (int i = 0; i < 1000; ++i) {
    GaitDesignInput in;
    in.run = 0.19 + 0.16 * unit(rng);
    in.rise = 0.10 + 0.15 * unit(rng);
    const double cl = std::hypot(in.run, in.rise);
    in.body_length = cl * (1.0 + unit(rng));  // CL < BL < 2 CL, the paper's assumption
    const double l_min = MinLegLength(in.run, in.rise);
    in.max_leg_length = 0.5 * cl + (1.5 * l_min - 0.5 * cl) * unit(rng);  // some shorter than l_min
    in.buffer = 0.9 * unit(rng);
    const GaitDesign g = DesignGait(in);
    // (11)-(13) straight from D_o: rem(BL, CL) = BL - CL in this range.
    const bool c11 = in.body_length - cl + g.d_o <= cl;
    const bool c12 = in.body_length - cl >= g.d_o;
    const bool c13 = in.max_leg_length > l_min;
    const double bl = in.body_length;
    const DimensionlessVerdict v = EvaluateDimensionless({in.run / bl, in.rise / bl, in.max_leg_length / bl, in.buffer});
    INFO("design " << i << ": W " << in.run << " H " << in.rise << " BL " << bl << " l_max " << in.max_leg_length << " p " << in.buffer);
    REQUIRE(v.in_body_range);
    CHECK(v.c14 == c11);
    CHECK(v.c15 == c12);
    CHECK(v.c16 == c13);
    // And the verdict of the design itself, (8)-(10) with the remainder.
    CHECK(v.feasible() == (g.conditions[0].holds && g.conditions[1].holds && g.conditions[2].holds));
    agree += v.c14 == c11 && v.c15 == c12 && v.c16 == c13;
    holds14 += v.c14;
    holds15 += v.c15;
    holds16 += v.c16;
    feasible += v.feasible();
  }
  CHECK(agree == 1000);
  // Every condition both holds and fails somewhere in the sample, so each comparison has teeth.
  for (int n : {holds14, holds15, holds16, feasible}) {
    CHECK(n > 50);
    CHECK(n < 950);
  }
}

TEST_CASE("eqs. (14)-(16): the paper's three stairs lie in its robot's feasible region", "[gait]") {
  for (const MarkedStair& s : PaperStairs()) {
    INFO(s.label);
    CHECK(EvaluateDimensionless({s.run / 0.444, s.rise / 0.444, 0.21 / 0.444, 0.42}).feasible());
  }
  // A leg shorter than l_min (18.85 cm on 27 x 17) fails (16) only.
  const DimensionlessVerdict short_leg = EvaluateDimensionless({0.27 / 0.444, 0.17 / 0.444, 0.18 / 0.444, 0.42});
  CHECK_FALSE(short_leg.c16);
  CHECK(short_leg.c14);
  CHECK(short_leg.c15);
  CHECK_FALSE(EvaluateDimensionless({std::nan(""), 0.3, 0.4, 0.42}).feasible());
}

TEST_CASE("Figure 4(b): the feasible region, three curves, the paper's stairs and the codes", "[gait]") {
  const std::string svg = FeasibilityFigureSvg(0.21, 0.444, 0.42, PaperStairs());
  CHECK(svg.rfind("<svg", 0) == 0);
  CHECK(svg.find("l_max/BL = 0.473, p = 0.42") != std::string::npos);
  for (const char* label : {"27 x 17", "31 x 17.5", "28 x 16", "US residential", "US commercial", "UK private"}) {
    CHECK(svg.find(label) != std::string::npos);
  }
  for (const char* colour : {"#c0392b", "#2e6fd1", "#e08a00"}) {
    CHECK(svg.find(std::string("<g fill=\"") + colour + "\">\n<circle") != std::string::npos);  // each boundary drawn
  }
  CHECK_THROWS_AS(FeasibilityFigureSvg(0.21, 0.0, 0.42, {}), std::invalid_argument);
}
