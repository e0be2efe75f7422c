// BodyQp: without stability rows the sideways shift is solved as its own QP; the plan must be the
// one the joint QP (with free support rows) gives.
#include <catch2/catch.hpp>

#include <cmath>

#include "planning/body/body_qp.h"

using namespace stairplan;

namespace {

// Inputs of a climbing cycle, the same for any BodyQp: knot 0 pinned (with a sideways shift the
// plan must bring back), hip rows that bind around a step, trust boxes on pitch and shifts.
void FillInputs(BodyQp* qp) {
  const int n = qp->knots();
  for (int k = 0; k < n; ++k) {
    const double t = 0.025 * k;
    const double step = k < n / 2 ? 0.0 : 0.17;
    for (int l = 0; l < kBodyLegs; ++l) qp->height_ref[k * kBodyLegs + l] = 0.45 + (l < 2 ? step : 0.5 * step);
    qp->pitch_ref[k] = -0.3 * std::sin(2.0 * t);
    qp->shift_ref[k] = 0.03;
    qp->lateral_ref[k] = 0.0;
    qp->pitch_lo[k] = -0.4, qp->pitch_hi[k] = 0.1;
    qp->shift_lo[k] = -0.01, qp->shift_hi[k] = 0.02;
    qp->lateral_lo[k] = -0.006, qp->lateral_hi[k] = 0.006;
    for (int g = 0; g < qp->groups(); ++g) {
      qp->hip_lo[k * qp->groups() + g] = 0.40 + 0.6 * step;
      qp->hip_hi[k * qp->groups() + g] = 0.50 + step;
    }
  }
  qp->z_lo[0] = qp->z_hi[0] = 0.45;
  qp->pitch_lo[0] = qp->pitch_hi[0] = 0.0;
  qp->shift_lo[0] = qp->shift_hi[0] = 0.0;
  qp->lateral_lo[0] = qp->lateral_hi[0] = 0.005;
}

}  // namespace

TEST_CASE("the sideways shift solved apart gives the joint QP's plan", "[body][qp]") {
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  BodyPlannerSettings apart_settings;  // stability_margin < 0 by default: no support rows
  REQUIRE(apart_settings.stability_margin < 0.0);
  BodyPlannerSettings joint_settings;
  joint_settings.stability_margin = 0.0;  // support rows exist (left free here)
  BodyQp apart(apart_settings, c), joint(joint_settings, c);
  REQUIRE(apart.lateral_apart());
  REQUIRE_FALSE(joint.lateral_apart());
  const int n = apart.knots();
  CHECK(apart.program().num_variables() == 3 * n);
  CHECK(apart.lateral_program().num_variables() == n);
  CHECK(joint.program().num_variables() == 4 * n);
  FillInputs(&apart);
  FillInputs(&joint);
  optim::SolveResult a, j;
  // Twice: the second solve of each is warm, as in the control loop.
  for (int pass = 0; pass < 2; ++pass) {
    apart.Solve(optim::kInf, &a);
    joint.Solve(optim::kInf, &j);
    REQUIRE(a.solved());
    REQUIRE(j.solved());
    const auto same = [&](const optim::VariableBlock& ba, const optim::VariableBlock& bj) {
      return (a.x.segment(ba.start, n) - j.x.segment(bj.start, n)).lpNorm<Eigen::Infinity>();
    };
    CHECK(same(apart.z(), joint.z()) < 1e-9);
    CHECK(same(apart.pitch(), joint.pitch()) < 1e-9);
    CHECK(same(apart.shift(), joint.shift()) < 1e-9);
    CHECK((apart.LateralOf(a) - joint.LateralOf(j)).lpNorm<Eigen::Infinity>() < 1e-9);
    // The pinned sideways shift decays toward 0 inside its trust box: the lateral QP did work.
    CHECK(apart.LateralOf(a)[0] == Approx(0.005));
    CHECK(std::abs(apart.LateralOf(a)[n - 1]) < 0.005);
  }
}
