// The leg rows carried from one cycle to the next (stairplan/planning/body/knot_row_cache.h): taken over only
// at the same instant (the passing rows: the same interval, for the same legs) and near the same
// centre, their relaxation re-evaluated there; and over a climb, plans made with them are the plans
// made without, at a fraction of the linearisations.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/body/knot_row_cache.h"
#include "stairplan/planning/crawl_planner.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

constexpr double kDt = 0.025;
constexpr int kKnots = 40;

// Knot k's leg rows filled with distinct values: a joint row broken from below at v0, one from
// above, one held, a free one; a clearance row broken at v0 and a free one.
void FillKnot(BodyQp& qp, int k) {
  const int s = BodyQp::StanceRow(k, 0, 0), c = BodyQp::ClearanceRow(k, 0);
  for (int r = 0; r < kBodyLegs * BodyQp::kStanceRows; ++r) {
    qp.stance.a.row(s + r) << 1.0 + r, -0.5, 0.25 * r, 0.1;
    qp.stance.lo[s + r] = -optim::kInf;
    qp.stance.hi[s + r] = optim::kInf;
  }
  qp.stance.lo[s + 0] = 10.0;  // a . v0 is far below
  qp.stance.hi[s + 1] = -10.0;  // far above
  qp.stance.lo[s + 2] = -10.0, qp.stance.hi[s + 2] = 10.0;
  for (int r = 0; r < BodyQp::kClearanceRows; ++r) {
    qp.clearance.a.row(c + r) << 0.0, 0.0, 1.0, 0.0;
    qp.clearance.lo[c + r] = -optim::kInf;
    qp.clearance.hi[c + r] = optim::kInf;
  }
  qp.clearance.lo[c + 4] = 0.5;
}

// A body QP with leg rows and a cache of its rows, taken over within max_move of their centre.
struct CacheCase {
  BodyPlannerSettings settings;
  BodyQp qp{settings, std::array<double, kBodyLegs>{-0.3, -0.3, 0.3, 0.3}, /*stance_rows=*/true};
  Eigen::Vector4d max_move{0.001, 0.005, 0.001, 0.0015};
  KnotRowCache cache{kKnots, kDt, max_move};
};

}  // namespace

TEST_CASE_METHOD(CacheCase, "leg rows are taken over at the same instant near the same centre, their relaxation re-evaluated",
          "[body][row_cache]") {
  const std::array<Eigen::Vector3d, kBodyLegs> q{Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.4, 0.5, 0.6),
                                                 Eigen::Vector3d(0.7, 0.8, 0.9), Eigen::Vector3d(1.0, 1.1, 1.2)};
  const Eigen::Vector4d v0(0.45, -0.2, 0.01, 0.0);
  // Stored as knot 12 at t = 3.3 s; the next cycle asks for it as knot 11, at the same instant
  // written another way (3.275 + 0.025).
  const double t = 132 * kDt;
  FillKnot(qp, 12);
  cache.Store(t, v0, 12, qp, q.data());
  cache.StoreComBase(t, Eigen::Vector2d(0.3, -0.02));
  std::array<Eigen::Vector3d, kBodyLegs> got{};
  const Eigen::Vector4d near = v0 + Eigen::Vector4d(0.0009, -0.004, 0.0009, -0.0014);
  REQUIRE(cache.Restore(131 * kDt + kDt, near, 11, qp, got.data()));
  for (int l = 0; l < kBodyLegs; ++l) CHECK(got[static_cast<std::size_t>(l)] == q[static_cast<std::size_t>(l)]);
  const int s11 = BodyQp::StanceRow(11, 0, 0), s12 = BodyQp::StanceRow(12, 0, 0);
  for (int r = 0; r < kBodyLegs * BodyQp::kStanceRows; ++r) {
    INFO("stance row " << r);
    CHECK(qp.stance.a.row(s11 + r) == qp.stance.a.row(s12 + r));
    CHECK(qp.stance.lo[s11 + r] == qp.stance.lo[s12 + r]);
    CHECK(qp.stance.hi[s11 + r] == qp.stance.hi[s12 + r]);
  }
  // The relaxation is what the new centre breaks, not what the old one did.
  const Eigen::Vector4d a0 = qp.stance.a.row(s11).transpose(), a1 = qp.stance.a.row(s11 + 1).transpose();
  CHECK(qp.stance.sigma[s11] == Approx(10.0 - a0.dot(near)));
  CHECK(qp.stance.sigma[s11 + 1] == Approx(-10.0 - a1.dot(near)));
  CHECK(qp.stance.sigma[s11 + 2] == 0.0);
  CHECK(qp.stance.sigma[s11 + 3] == 0.0);
  const int c11 = BodyQp::ClearanceRow(11, 0);
  CHECK(qp.clearance.lo[c11 + 4] == 0.5);
  CHECK(qp.clearance.sigma[c11 + 4] == Approx(0.5 - near[2]));
  CHECK(qp.clearance.sigma[c11] == 0.0);
  Eigen::Vector2d com;
  REQUIRE(cache.ComBase(t, &com));
  CHECK(com == Eigen::Vector2d(0.3, -0.02));

  // Not taken over: a centre moved beyond max_move in any one variable, another instant (between
  // knots, or the one a whole ring of slots later), or after the instant was stored again
  // (which forgets its centre of mass until that is stored too).
  qp.stance.lo[s11] = 123.0;
  for (int v = 0; v < 4; ++v) {
    Eigen::Vector4d far = v0;
    far[v] += 1.01 * max_move[v];
    INFO("variable " << v);
    CHECK_FALSE(cache.Restore(t, far, 11, qp, got.data()));
  }
  CHECK(qp.stance.lo[s11] == 123.0);  // nothing written
  CHECK_FALSE(cache.Restore(t + 0.5 * kDt, v0, 11, qp, got.data()));
  CHECK_FALSE(cache.Restore(t + (kKnots + 1) * kDt, v0, 11, qp, got.data()));
  CHECK_FALSE(cache.ComBase(t + (kKnots + 1) * kDt, &com));
  cache.Store(t, v0, 12, qp, q.data());
  CHECK_FALSE(cache.ComBase(t, &com));
}

TEST_CASE_METHOD(CacheCase, "passing rows are taken over for the same interval near the same centre when they cover the legs asked for",
          "[body][row_cache]") {
  // Interval 7's clearance rows 0-4 (row 1 free).
  const int p7 = BodyQp::ClearanceRow(7, 0), p6 = BodyQp::ClearanceRow(6, 0);
  for (int r = 0; r < BodyQp::kClearanceRows; ++r) {
    qp.passing.a.row(p7 + r) << 0.0, 0.1 * r, 1.0, 0.0;
    qp.passing.lo[p7 + r] = r == 1 ? -optim::kInf : 0.01 * r;
    qp.passing.hi[p7 + r] = optim::kInf;
  }
  const Eigen::Vector4d v0(0.45, -0.2, 0.01, 0.0);
  const unsigned legs_0_2_3 = 1u << 0 | 1u << 2 | 1u << 3, body = 1u << kBodyLegs;
  // Stored with rows for legs 0, 2, 3 and the body, for the interval from knot 7 at t = 2 s; the
  // next cycle asks for it as interval 6, with rows for leg 2 and the body.
  const double t = 80 * kDt;
  cache.StorePassing(t, v0, legs_0_2_3 | body, 7, qp);
  const Eigen::Vector4d near = v0 + Eigen::Vector4d(0.0, 0.0, 0.0009, 0.0);
  REQUIRE(cache.RestorePassing(79 * kDt + kDt, near, 1u << 2 | body, 6, qp));
  for (int r = 0; r < BodyQp::kClearanceRows; ++r) {
    INFO("passing row " << r);
    if (r == 2 || r == kBodyLegs) {
      CHECK(qp.passing.a.row(p6 + r) == qp.passing.a.row(p7 + r));
      CHECK(qp.passing.lo[p6 + r] == qp.passing.lo[p7 + r]);
      // Relaxed by what the new centre breaks (a . near = near[2] + 0.1 r near[1]).
      CHECK(qp.passing.sigma[p6 + r] == Approx(0.01 * r - (near[2] + 0.1 * r * near[1])));
    } else {
      // Not asked for: no row, as when linearised afresh.
      CHECK(qp.passing.lo[p6 + r] == -optim::kInf);
      CHECK(qp.passing.sigma[p6 + r] == 0.0);
    }
  }
  // Not taken over: a leg that had no row then (leg 1), a centre moved too far, another interval.
  qp.passing.lo[p6] = 123.0;
  CHECK_FALSE(cache.RestorePassing(t, v0, 1u << 1 | 1u << 2, 6, qp));
  Eigen::Vector4d far = v0;
  far[2] += 1.01 * max_move[2];
  CHECK_FALSE(cache.RestorePassing(t, far, 1u << 2, 6, qp));
  CHECK_FALSE(cache.RestorePassing(t + kDt, v0, 1u << 2, 6, qp));
  CHECK_FALSE(cache.RestorePassing(t + (kKnots + 1) * kDt, v0, 1u << 2, 6, qp));
  CHECK(qp.passing.lo[p6] == 123.0);  // nothing written
}

TEST_CASE("over a climb the rows carried across cycles give the plan of fresh ones, from a third of the linearisations",
          "[body][row_cache][stance_rows]") {
  const RobotModel& robot = BuiltinRobot();
  StairSpec spec;
  spec.steps = 2;
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const Plan footsteps = PlanCrawl(robot, stairs, map);
  REQUIRE(footsteps.status == PlanStatus::kOk);
  // The receding horizon run forward as PlanBody runs it, over the first 1.5 s under the
  // sanitizers (the warm-up and the first swing; 5 s took a minute there) and the whole flight
  // otherwise.
  const auto run = [&](double share, int* linearised, int* reused) {
    BodyPlannerSettings settings;
    settings.stance_rows = true;
    settings.stability_margin = 0.03;
    settings.relinearise_share = share;
    settings.cycle_budget_s = 10.0;
    BodyPlanner planner(robot, stairs, map, footsteps, settings);
    const double end = testing::FullOrSanitized(planner.schedule().end_time(), 1.5);
    std::vector<BodyState> body;
    BodyState state = planner.StartState();
    for (int c = 0; c * kDt <= end; ++c) {
      const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, c * kDt);
      CHECK(out.status == BodyPlanStatus::kOk);
      *linearised += out.linearised_knots;
      *reused += out.reused_knots;
      body.push_back(out.knots[0]);
      state = planner.Interpolate((c + 1) * kDt);
    }
    return body;
  };
  int fresh_linearised = 0, fresh_reused = 0, linearised = 0, reused = 0;
  const std::vector<BodyState> fresh = run(0.0, &fresh_linearised, &fresh_reused);
  const std::vector<BodyState> carried = run(0.25, &linearised, &reused);
  CHECK(fresh_reused == 0);
  CHECK(fresh_linearised == 0);  // without the cache nothing is counted
  INFO(reused << " of " << linearised << " knots taken over");
  CHECK(reused > 2 * (linearised - reused));
  REQUIRE(carried.size() == fresh.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    worst = std::max({worst, std::abs(carried[i].z - fresh[i].z), std::abs(carried[i].com_shift - fresh[i].com_shift),
                      std::abs(carried[i].com_shift_y - fresh[i].com_shift_y),
                      0.1 * std::abs(carried[i].pitch - fresh[i].pitch)});  // 0.1 m lever
  }
  INFO("largest difference " << worst * 1000 << " mm");
  CHECK(worst < 0.003);  // 1.6 mm measured on the whole flight
}
