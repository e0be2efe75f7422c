// BodyQp: without stability rows the sideways shift is solved as its own QP; the plan must be the
// one the joint QP (with free support rows) gives.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/planning/body/body_qp.h"

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

// Inputs of the cycle whose knot 0 is knot `first` of a longer flight, the same function of the
// flight's time at every cycle: a step at flight knot 50 the hip rows bind around, pitch and a
// forward shift that reach their bounds over stretches of knots, no knot pinned.
void FillFlightInputs(BodyQp* qp, int first) {
  const int n = qp->knots();
  for (int k = 0; k < n; ++k) {
    const int f = first + k;
    const double t = 0.025 * f;
    const double step = f < 50 ? 0.0 : 0.17;
    for (int l = 0; l < kBodyLegs; ++l) qp->height_ref[k * kBodyLegs + l] = 0.45 + (l < 2 ? step : 0.5 * step);
    qp->pitch_ref[k] = -0.5 * std::sin(3.0 * t);
    qp->shift_ref[k] = 0.04 * std::sin(5.0 * t);
    qp->lateral_ref[k] = 0.01 * std::cos(4.0 * t);
    qp->pitch_lo[k] = -0.3, qp->pitch_hi[k] = 0.3;
    qp->shift_lo[k] = -0.02, qp->shift_hi[k] = 0.02;
    qp->lateral_lo[k] = -0.006, qp->lateral_hi[k] = 0.006;
    for (int g = 0; g < qp->groups(); ++g) {
      qp->hip_lo[k * qp->groups() + g] = 0.40 + 0.6 * step;
      qp->hip_hi[k * qp->groups() + g] = 0.50 + step;
    }
  }
}

}  // namespace

TEST_CASE("a warm start moved with the horizon reaches the cold optimum with fewer changes than the unmoved one",
          "[body][qp]") {
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  // With leg rows (one QP), and without stability or leg rows (the sideways shift apart, whose
  // own QP is not moved).
  for (const bool stance_rows : {true, false}) {
    INFO("stance rows " << stance_rows);
    BodyPlannerSettings settings;
    if (stance_rows) settings.stability_margin = 0.0;
    // Three planners over the same flight: one moves its warm start with the horizon, one keeps
    // it where it was, one solves every cycle cold.
    BodyQp moved(settings, c, stance_rows), kept(settings, c, stance_rows), cold(settings, c, stance_rows);
    REQUIRE(moved.lateral_apart() == !stance_rows);
    const int n = moved.knots();
    optim::SolveResult rm, rk, rc;
    int moved_changes = 0, kept_changes = 0;
    for (int cycle = 0; cycle < 40; ++cycle) {
      if (cycle > 0) moved.ShiftWarmStart(rm.active_set, 1);
      cold.ResetWarmStart();
      for (BodyQp* qp : {&moved, &kept, &cold}) FillFlightInputs(qp, cycle);
      moved.Solve(optim::kInf, &rm);
      kept.Solve(optim::kInf, &rk);
      cold.Solve(optim::kInf, &rc);
      REQUIRE(rm.solved());
      REQUIRE(rk.solved());
      REQUIRE(rc.solved());
      CHECK((rm.x - rc.x).lpNorm<Eigen::Infinity>() < 1e-8);
      CHECK((rk.x - rc.x).lpNorm<Eigen::Infinity>() < 1e-8);
      CHECK((moved.LateralOf(rm) - cold.LateralOf(rc)).lpNorm<Eigen::Infinity>() < 1e-8);
      if (cycle > 0) {
        moved_changes += rm.info.iterations;
        kept_changes += rk.info.iterations;
      }
    }
    // The bounds bind over stretches of knots (pitch, shift, the hips at the step), so there is
    // an active set to carry: what was active at knot k + 1 is active at knot k now.
    int active = 0;
    for (const optim::ActiveSide side : rc.active_set.bounds) active += side != 0;
    for (const optim::ActiveSide side : rc.active_set.rows) active += side != 0;
    CHECK(active > n / 2);
    INFO("changes over 39 cycles: moved " << moved_changes << ", kept " << kept_changes);
    CHECK(2 * moved_changes < kept_changes);
  }
}

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

TEST_CASE("a row the knot cannot hold is relaxed at the exact penalty, and rows that can hold are kept exactly",
          "[body][qp]") {
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  BodyPlannerSettings settings;
  BodyQp qp(settings, c, /*stance_rows=*/true);
  REQUIRE(qp.has_stance_rows());
  REQUIRE_FALSE(qp.lateral_apart());
  const int n = qp.knots();
  FillInputs(&qp);
  // Knot 10, leg 0: height at least 2 m, out of reach of the acceleration limits from 0.45 m.
  const int bad = BodyQp::StanceRow(10, 0, 3);
  qp.stance.a.row(bad) << 1.0, 0.0, 0.0, 0.0;
  qp.stance.lo[bad] = 2.0;
  qp.stance.hi[bad] = optim::kInf;
  qp.stance.sigma[bad] = 2.0 - 0.45;  // what the previous plan, z = 0.45 m, breaks it by
  // Knot 20, leg 1: the forward shift at most 1 mm, which the trust box allows.
  const int good = BodyQp::StanceRow(20, 1, 0);
  qp.stance.a.row(good) << 0.0, 0.0, 1.0, 0.0;
  qp.stance.lo[good] = -optim::kInf;
  qp.stance.hi[good] = 0.001;
  qp.stance.sigma[good] = 0.0;  // the previous plan holds it
  optim::SolveResult r;
  qp.Solve(optim::kInf, &r);
  REQUIRE(r.solved());
  const auto relax = r.x.segment(qp.relax().start, n);
  const double z10 = r.x[qp.z().start + 10];
  // The relaxation makes up exactly what the row misses, and nowhere else is any needed.
  CHECK(relax[10] * (2.0 - 0.45) == Approx(2.0 - z10).margin(1e-6));
  CHECK(relax[10] > 0.5);
  CHECK(relax[10] <= 1.0);
  for (int k = 0; k < n; ++k) {
    if (k != 10) CHECK(relax[k] < 1e-7);
  }
  CHECK(r.x[qp.shift().start + 20] <= 0.001 + 1e-9);
  // And that row mattered: freed, the plan goes past it.
  qp.stance.hi[good] = optim::kInf;
  qp.Solve(optim::kInf, &r);
  REQUIRE(r.solved());
  CHECK(r.x[qp.shift().start + 20] > 0.002);
}

TEST_CASE("a support row the sideways bound keeps from its full margin gives up only the shortfall, down to the floor",
          "[body][qp]") {
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  BodyPlannerSettings settings;
  settings.stability_margin = 0.03;
  settings.min_stability_margin = 0.015;  // at most 15 mm to give
  BodyQp qp(settings, c, /*stance_rows=*/true);
  const int n = qp.knots();
  FillInputs(&qp);  // |lateral| <= 6 mm past knot 0
  const auto row = [&](int k, double lo, double hi, double sigma) {
    const int r = k * BodyQp::kSupportRows;
    qp.support_cx[r] = 0.0;
    qp.support_cy[r] = 1.0;
    qp.support_lo[r] = lo;
    qp.support_hi[r] = hi;
    qp.support_sigma[r] = sigma;
  };
  row(10, 0.016, optim::kInf, 0.0);    // lateral >= 16 mm: 10 mm short
  row(20, -optim::kInf, -0.012, 0.0);  // lateral <= -12 mm: 6 mm short
  row(30, 0.025, optim::kInf, 0.025);  // 19 mm short: the floor holds 4 mm, which the relaxation keeps
  optim::SolveResult r;
  qp.Solve(optim::kInf, &r);
  REQUIRE(r.solved());
  const auto give = r.x.segment(qp.give().start, n);
  const auto relax = r.x.segment(qp.relax().start, n);
  const auto lateral = qp.LateralOf(r);
  CHECK(give[10] == Approx(0.010).margin(1e-7));
  CHECK(lateral[10] == Approx(0.006).margin(1e-9));
  CHECK(give[20] == Approx(0.006).margin(1e-7));
  CHECK(lateral[20] == Approx(-0.006).margin(1e-9));
  CHECK(give[30] == Approx(0.015).margin(1e-9));
  CHECK(relax[30] * 0.025 == Approx(0.025 - 0.015 - 0.006).margin(1e-7));
  for (int k = 0; k < n; ++k) {
    if (k != 10 && k != 20 && k != 30) CHECK(give[k] < 1e-7);
    if (k != 30) CHECK(relax[k] < 1e-7);
  }
}

TEST_CASE("a ZMP row holds the pendulum's ZMP over three knots, and what the limits cannot reach is the excursion",
          "[body][qp]") {
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  BodyPlannerSettings settings;
  settings.stability_margin = 0.03;
  const double h = 0.5;
  BodyQp qp(settings, c, /*stance_rows=*/true, h);
  const int n = qp.knots();
  REQUIRE(qp.zmp_rows().size == BodyQp::kSupportRows * n);
  const double alpha = h / (9.81 * settings.knot_dt * settings.knot_dt);
  CHECK(qp.zmp_weight() == Approx(alpha));
  const auto stencil = qp.ZmpStencil(10);
  CHECK(stencil[0] == Approx(-alpha));
  CHECK(stencil[1] == Approx(1.0 + 2.0 * alpha));
  CHECK(stencil[2] == Approx(-alpha));
  FillInputs(&qp);  // |lateral| <= 6 mm past knot 0
  // The sideways ZMP at knot 10 at least `lo`: the shift cannot get there (6 mm), the sideways
  // acceleration can, up to max_lateral_accel.
  const int row = 10 * BodyQp::kSupportRows;
  qp.support_cy[row] = 1.0;
  const auto zmp_of = [&](const optim::SolveResult& r) {
    const auto y = qp.LateralOf(r);
    return stencil[0] * y[9] + stencil[1] * y[10] + stencil[2] * y[11];
  };
  optim::SolveResult r;
  const double reachable = 0.006 + alpha * settings.max_lateral_accel * settings.knot_dt * settings.knot_dt;
  for (const double lo : {0.05, reachable + 0.1}) {
    qp.zmp_lo[row] = lo;
    qp.Solve(optim::kInf, &r);
    REQUIRE(r.solved());
    const auto excursion = r.x.segment(qp.excursion().start, n);
    const auto relax = r.x.segment(qp.relax().start, n);
    CHECK(zmp_of(r) + excursion[10] >= lo - 1e-9);
    // The excursion pays only for what the limits leave: nothing when the ZMP can get there.
    CHECK(excursion[10] == Approx(std::max(lo - reachable, 0.0)).margin(1e-6));
    CHECK(relax.cwiseAbs().maxCoeff() < 1e-7);  // the ZMP rows never take the relaxation
    for (int k = 0; k < n; ++k) {
      if (k != 10) CHECK(excursion[k] < 1e-7);
    }
  }
}

TEST_CASE("knot 1's acceleration from the executed body is priced like every other knot's", "[body][qp]") {
  // The cost's second difference centred at knot 0, (x_1 - straight)^2 with straight = 2 x_0 -
  // x_-1: without it each cycle could pick knot 1 (what the robot executes next) anywhere the
  // acceleration limit allows, and the executed body chattered between the limits.
  const std::array<double, kBodyLegs> c{-0.3, -0.3, 0.3, 0.3};
  BodyPlannerSettings settings;
  settings.stability_margin = -1.0;
  settings.stance_rows = false;
  settings.acceleration_weight = 1.0;
  const auto knot1 = [&](double straight) {
    BodyQp qp(settings, c);
    FillInputs(&qp);
    qp.straight = {0.45, 0.0, straight, 0.005};
    optim::SolveResult r;
    qp.Solve(optim::kInf, &r);
    REQUIRE(r.solved());
    return r.x[qp.shift().start + 1];
  };
  // Knot 0 pinned at shift 0: the straight line ahead or behind pulls knot 1 that way, within the
  // trust box [-0.01, 0.02].
  const double ahead = knot1(0.004), level = knot1(0.0), behind = knot1(-0.004);
  INFO("knot 1 shift: behind " << behind << ", level " << level << ", ahead " << ahead);
  CHECK(ahead > level + 1e-4);
  CHECK(behind < level - 1e-4);
}
