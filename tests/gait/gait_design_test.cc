// The gait design against the 2012 paper's numbers (seed 003) and the interference conditions
// (8)-(10) in general, with rem(BL, CL) for any body length.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "stairplan/planning/gait/gait_design.h"

using namespace stairplan;

namespace {

// The paper's robot (Quattroped): BL = 44.4 cm, l_max = 21 cm, p = 42 %.
GaitDesignInput PaperRobot(double run, double rise) {
  GaitDesignInput in;
  in.run = run;
  in.rise = rise;
  in.max_leg_length = 0.21;
  in.body_length = 0.444;
  in.buffer = 0.42;
  return in;
}

const GaitCondition& Named(const GaitDesign& g, const std::string& name) {
  for (const GaitCondition& c : g.conditions) {
    if (name == c.name) return c;
  }
  FAIL("no condition " << name);
  return g.conditions[0];
}

}  // namespace

TEST_CASE("eq. (1): l_min for the paper's nominal stairs is 18.85 cm", "[gait]") {
  CHECK(MinLegLength(0.27, 0.17) == Approx(0.1885).margin(0.00005));
  // The three forms of eq. (1) agree.
  const double W = 0.27, H = 0.17, cl = std::hypot(W, H), phi = std::atan2(H, W);
  CHECK(MinLegLength(W, H) == Approx(0.5 * cl / std::cos(phi)).epsilon(1e-12));
  CHECK(MinLegLength(W, H) == Approx(0.5 * (W + H * std::tan(phi))).epsilon(1e-12));
  CHECK(DesignGait(PaperRobot(W, H)).l_min == Approx(0.188519).margin(1e-6));
}

TEST_CASE("eqs. (3)-(4): the contact offset at l_min reduces to l_min - d csc(phi)", "[gait]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> rise(0.10, 0.25), run(0.19, 0.35), d(0.0, 0.1);
  for (int i = 0; i < 200; ++i) {
    const double W = run(rng), H = rise(rng), dd = d(rng);
    const double cl = std::hypot(W, H);
    const double l_min = MinLegLength(W, H);
    CHECK(ContactOffset(l_min, dd, W, H) == Approx(l_min - dd * cl / H).margin(1e-9));
    // a grows with l and shrinks with d (the paper's two trends).
    CHECK(ContactOffset(l_min + 0.02, dd, W, H) > ContactOffset(l_min, dd, W, H));
    CHECK(ContactOffset(l_min, dd + 0.01, W, H) < ContactOffset(l_min, dd, W, H));
  }
  CHECK(std::isnan(ContactOffset(0.1, 0.0, 0.27, 0.17)));  // shorter than CL / 2
}

TEST_CASE("eqs. (5)-(7): D_s is the hip travel between the two contact offsets", "[gait]") {
  const GaitDesign g = DesignGait(PaperRobot(0.27, 0.17));
  // D_s = (a_max - a_min) cos(phi): the right leg swings at l_min, the left one at l_max.
  CHECK(g.d_s == Approx((g.a_max - g.a_min) * std::cos(g.phi)).epsilon(1e-9));
  CHECK(g.d_s == Approx(0.05737).margin(0.00001));
  CHECK(g.d_i == Approx(0.58 * g.d_s).epsilon(1e-12));
  CHECK(g.d_o == Approx(1.58 * g.d_s).epsilon(1e-12));
  CHECK(g.d_o == Approx(g.d_i + g.d_s).epsilon(1e-12));
  CHECK(g.cl == Approx(0.319061).margin(1e-6));
  // The paper's simulation (d = 8.5 cm): the right foot lands 2.9 cm from the edge.
  CHECK(g.d == Approx(0.085));
  CHECK(g.a_min == Approx(0.029).margin(0.0005));
}

TEST_CASE("the paper's robot is feasible on its nominal and both test staircases", "[gait]") {
  for (const auto& [run, rise] : {std::pair{0.27, 0.17}, std::pair{0.31, 0.175}, std::pair{0.28, 0.16}}) {
    CAPTURE(run, rise);
    const GaitDesign g = DesignGait(PaperRobot(run, rise));
    CHECK(g.feasible);
    for (const GaitCondition& c : g.conditions) {
      CAPTURE(c.name);
      CHECK(c.holds);
    }
    CHECK_FALSE(g.binding.empty());
  }
}

TEST_CASE("l_max <= l_min is infeasible and names condition (10)", "[gait]") {
  for (double l_max : {0.10, 0.17, 0.185, MinLegLength(0.27, 0.17)}) {
    CAPTURE(l_max);
    GaitDesignInput in = PaperRobot(0.27, 0.17);
    in.max_leg_length = l_max;
    const GaitDesign g = DesignGait(in);
    CHECK_FALSE(g.feasible);
    CHECK(g.binding == "(10)");
    CHECK_FALSE(Named(g, "(10)").holds);
  }
}

TEST_CASE("(8) and (9) bind at the right body lengths, for any multiple of CL", "[gait]") {
  GaitDesignInput in = PaperRobot(0.27, 0.17);
  const GaitDesign base = DesignGait(in);
  for (int k = 0; k < 4; ++k) {
    CAPTURE(k);
    // rem just below D_o: the front pair is still swinging when the hind pair must start.
    in.body_length = k * base.cl + base.d_o - 0.005;
    if (in.body_length > 0.0) {
      const GaitDesign g = DesignGait(in);
      CHECK_FALSE(g.feasible);
      CHECK(g.binding == "(9)");
      CHECK(Named(g, "(9)").slack == Approx(-0.005).margin(1e-9));
    }
    // rem + D_o just above CL: the hind pair overruns into the next front swing.
    in.body_length = (k + 1) * base.cl - base.d_o + 0.005;
    const GaitDesign g8 = DesignGait(in);
    CHECK_FALSE(g8.feasible);
    CHECK(g8.binding == "(8)");
  }
}

TEST_CASE("for CL < BL < 2CL the general conditions equal the paper's (11)-(12)", "[gait]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> rise(0.10, 0.25), run(0.19, 0.35), lmax(0.15, 0.40), p(0.0, 0.9), u(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    GaitDesignInput in;
    in.rise = rise(rng);
    in.run = run(rng);
    in.max_leg_length = lmax(rng);
    in.buffer = p(rng);
    const double cl = std::hypot(in.run, in.rise);
    in.body_length = cl * (1.0 + u(rng));
    const GaitDesign g = DesignGait(in);
    if (!Named(g, "(10)").holds) continue;
    ++checked;
    const bool eq11 = (in.body_length - cl) + g.d_o <= cl + 1e-12;
    const bool eq12 = (in.body_length - cl) >= g.d_o - 1e-12;
    CHECK(Named(g, "(8)").holds == eq11);
    CHECK(Named(g, "(9)").holds == eq12);
    // Adding whole CLs to the body changes nothing.
    in.body_length += 2.0 * cl;
    const GaitDesign g2 = DesignGait(in);
    CHECK(Named(g2, "(8)").holds == eq11);
    CHECK(Named(g2, "(9)").holds == eq12);
  }
  CHECK(checked > 500);
}

TEST_CASE("a hip clearance too large for the stairs puts the right feet off the tread", "[gait]") {
  GaitDesignInput in = PaperRobot(0.27, 0.17);
  in.hip_clearance = 0.11;  // > l_min sin(phi) = 10.04 cm
  const GaitDesign g = DesignGait(in);
  CHECK(g.a_min < 0.0);
  CHECK_FALSE(g.feasible);
  CHECK(g.binding == "(4)");
}

TEST_CASE("bad design inputs throw naming the field", "[gait]") {
  GaitDesignInput in;
  in.run = -1.0;
  CHECK_THROWS_WITH(DesignGait(in), Catch::Contains("run"));
  in = GaitDesignInput{};
  in.buffer = 1.0;
  CHECK_THROWS_WITH(DesignGait(in), Catch::Contains("buffer"));
  in = GaitDesignInput{};
  in.hip_clearance = std::nan("");
  CHECK_THROWS_WITH(DesignGait(in), Catch::Contains("hip_clearance"));
  in = GaitDesignInput{};
  in.body_length = 0.0;
  CHECK_THROWS_AS(DesignGait(in), std::invalid_argument);
}
