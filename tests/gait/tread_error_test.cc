// The tread-depth error tolerance of eqs. (17)-(19) against the paper's example.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/planning/gait/tread_error.h"

using namespace stairplan;

TEST_CASE("eq. (17): the paper's example tolerates 2.9 > dW > -12.05 cm", "[gait]") {
  // The paper prints d = 2.8 cm beside this example, but 2.8 cm is the standard deviation of W;
  // both bounds come out for d = 8.5 cm, the hip clearance of its simulation.
  GaitDesignInput in;
  in.run = 0.27;
  in.rise = 0.17;
  in.max_leg_length = 0.21;
  in.hip_clearance = 0.085;
  const GaitDesign g = DesignGait(in);
  const TreadErrorTolerance t = TreadDepthTolerance(g, in.run, in.rise);
  CHECK(t.upper == Approx(0.029).margin(0.0005));
  CHECK(t.lower == Approx(-0.1205).margin(0.0005));
  CHECK(t.upper == Approx(g.a_min));
}

TEST_CASE("eq. (17): no tolerance without a gait (condition (10) fails)", "[gait]") {
  GaitDesignInput in;
  in.max_leg_length = 0.18;
  const TreadErrorTolerance t = TreadDepthTolerance(DesignGait(in), in.run, in.rise);
  CHECK(std::isnan(t.lower));
  CHECK(std::isnan(t.upper));
  // Nothing lies within a NaN range.
  CHECK_FALSE(CheckCumulativeTreadError({0.0}, t).within());
}

TEST_CASE("eq. (17): a larger hip clearance narrows the tolerance", "[gait]") {
  GaitDesignInput in;
  double previous_upper = 1e9;
  for (double d : {0.02, 0.04, 0.06, 0.08}) {
    in.hip_clearance = d;
    const TreadErrorTolerance t = TreadDepthTolerance(DesignGait(in), in.run, in.rise);
    CHECK(t.lower < t.upper);
    CHECK(t.upper < previous_upper);
    previous_upper = t.upper;
  }
}

TEST_CASE("eq. (19): errors accumulate and the first step out of range is named", "[gait]") {
  const TreadErrorTolerance t{0.029, -0.1205};
  // Each tread 1 cm deeper than designed: the 3rd tread still fits (2.9 cm > 3 cm fails).
  const CumulativeTreadError deeper = CheckCumulativeTreadError({0.01, 0.01, 0.01, 0.01}, t);
  REQUIRE(deeper.cumulative.size() == 4);
  CHECK(deeper.cumulative[3] == Approx(0.04));
  CHECK(deeper.first_violation == 2);
  CHECK_FALSE(deeper.within());
  // Errors that cancel never accumulate.
  const CumulativeTreadError mixed = CheckCumulativeTreadError({0.02, -0.02, 0.02, -0.02, 0.02}, t);
  CHECK(mixed.within());
  // Shallower treads: the lower bound.
  const CumulativeTreadError shallow = CheckCumulativeTreadError({-0.05, -0.05, -0.05}, t);
  CHECK(shallow.first_violation == 2);
  CHECK_THROWS_WITH(CheckCumulativeTreadError({0.0, std::nan("")}, t), Catch::Contains("errors[1]"));
}
