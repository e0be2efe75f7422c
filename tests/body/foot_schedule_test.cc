// The feet's timeline read from a footstep plan: stances, swings, the neutral body and the slope.
#include <catch2/catch.hpp>

#include "stairplan/kinematics/builtin_robot.h"
#include <algorithm>
#include <limits>

#include "stairplan/planning/body/foot_schedule.h"

using namespace stairplan;

namespace {

// Four feet on flat ground at the robot's neutral offsets and one LF step of 0.2 m in [1, 1.5] s.
Plan OneStep(const RobotModel& robot) {
  Plan plan;
  plan.facing = Facing::kForward;
  for (const LegModel& leg : robot.legs()) {
    plan.legs.push_back(leg.name);
    plan.initial_feet_W.emplace_back(leg.hip_B.x(), leg.foot_zero_B.y(), 0.0);
  }
  Footstep step;
  step.leg = "LF";
  step.t_liftoff = 1.0;
  step.t_touchdown = 1.5;
  step.from_W = plan.initial_feet_W[0];
  step.position_W = step.from_W + Eigen::Vector3d(0.2, 0.0, 0.1);
  plan.footsteps.push_back(step);
  return plan;
}

// A crawl on flat ground: `cycles` times each leg in the paper's order (RH, LH, RF, LF) steps
// 0.2 m forward in a 0.45 s swing, each swing followed by 0.6 s with four feet down.
Plan FlatCrawl(const RobotModel& robot, int cycles) {
  Plan plan = OneStep(robot);
  plan.footsteps.clear();
  std::vector<Eigen::Vector3d> feet = plan.initial_feet_W;
  double t = 0.5;
  for (int c = 0; c < cycles; ++c) {
    for (const char* name : {"RH", "LH", "RF", "LF"}) {
      const auto l = static_cast<std::size_t>(
          std::find(plan.legs.begin(), plan.legs.end(), name) - plan.legs.begin());
      Footstep step;
      step.leg = name;
      step.t_liftoff = t;
      step.t_touchdown = t + 0.45;
      step.from_W = feet[l];
      feet[l].x() += 0.2;
      step.position_W = feet[l];
      plan.footsteps.push_back(step);
      t += 1.05;
    }
  }
  return plan;
}

}  // namespace

TEST_CASE("a leg stands, swings with interpolated foot, then stands on its new foothold", "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  const Plan plan = OneStep(robot);
  const FootSchedule schedule(robot, plan);
  REQUIRE(schedule.footholds().size() == 5);
  CHECK(schedule.end_time() == Approx(1.5));

  const LegPhase before = schedule.Phase(0, 0.5);
  CHECK(before.stance);
  CHECK(before.foothold == 0);
  CHECK(before.next_foothold == 4);
  CHECK(before.t_liftoff == Approx(1.0));

  const LegPhase swing = schedule.Phase(0, 1.25);
  CHECK_FALSE(swing.stance);
  CHECK(swing.progress == Approx(0.5));
  CHECK((swing.foot_W - (plan.initial_feet_W[0] + Eigen::Vector3d(0.1, 0.0, 0.05))).norm() < 1e-12);

  const LegPhase after = schedule.Phase(0, 2.0);
  CHECK(after.stance);
  CHECK(after.foothold == 4);
  CHECK(after.next_foothold == -1);
  CHECK((after.foot_W - plan.footsteps[0].position_W).norm() < 1e-12);
  // The other legs never move.
  for (int l = 1; l < 4; ++l) CHECK(schedule.Phase(l, 1.25).stance);
}

TEST_CASE("the feet centre sits over the feet and the feet's slope is their pitch", "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  const Plan plan = OneStep(robot);
  const FootSchedule schedule(robot, plan);
  CHECK(schedule.FeetCentreXY(0.0).norm() < 1e-12);
  // After the step the LF foot is 0.2 m ahead: the body moves a quarter of it.
  CHECK(schedule.FeetCentreXY(2.0).x() == Approx(0.05));
  // Half a swing away from the swing the neutral body is the feet centre.
  CHECK(schedule.smoothing_window() == Approx(0.5));
  CHECK(schedule.NeutralBodyXY(0.7).norm() < 1e-12);
  CHECK(schedule.NeutralBodyXY(1.8).x() == Approx(0.05));
  CHECK(schedule.FeetPitch(0.0) == Approx(0.0).margin(1e-12));
  // One front foot 0.1 m higher over the body length (+0.1 m): front mean +0.05 m, nose-up negative.
  const double run = 2.0 * robot.legs()[0].hip_B.x() + 0.1;
  CHECK(schedule.FeetPitch(2.0) == Approx(-std::atan2(0.05, run)));
}

TEST_CASE("a malformed footstep plan names the offending footstep", "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  Plan plan = OneStep(robot);
  plan.footsteps[0].leg = "XX";
  CHECK_THROWS_WITH(FootSchedule(robot, plan), Catch::Contains("footsteps[0]"));
  plan = OneStep(robot);
  plan.footsteps[0].t_touchdown = 0.5;  // before its liftoff
  CHECK_THROWS_AS(FootSchedule(robot, plan), std::invalid_argument);
}

TEST_CASE("a swinging foot follows its swing trajectory: the footstep's apex, or the stairs' when it states none",
          "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  Plan plan = OneStep(robot);
  plan.footsteps[0].swing_apex_z = 0.3;
  const FootSchedule stated(robot, plan);
  const SwingTrajectory path(plan.footsteps[0].from_W, plan.footsteps[0].position_W, 0.3);
  for (const double t : {1.0, 1.1, 1.25, 1.4, 1.49}) {
    const LegPhase phase = stated.Phase(0, t);
    REQUIRE_FALSE(phase.stance);
    INFO("t = " << t);
    CHECK((stated.SwingFoot(0, phase) - path.At(phase.progress)).norm() < 1e-12);
  }
  // Mid-swing the foot is at the apex, above the straight line the neutral body follows.
  CHECK(stated.SwingFoot(0, stated.Phase(0, 1.25)).z() == Approx(0.3));
  // In stance it is the foothold.
  const LegPhase stance = stated.Phase(1, 1.25);
  CHECK((stated.SwingFoot(1, stance) - stance.foot_W).norm() == 0.0);

  // No apex stated: the stairs' (the highest obstacle plus the clearance), as the validator has it.
  plan.footsteps[0].swing_apex_z = std::numeric_limits<double>::quiet_NaN();
  StairSpec spec;
  const Staircase stairs(spec);
  const FootSchedule derived(robot, plan, &stairs);
  const SwingTrajectory from_stairs(plan.footsteps[0].from_W, plan.footsteps[0].position_W, stairs);
  CHECK(derived.SwingFoot(0, derived.Phase(0, 1.25)).z() == Approx(from_stairs.apex_z()));
}

TEST_CASE("the neutral body is the feet centre averaged over a swing: smooth, and near the feet", "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  const FootSchedule schedule(robot, FlatCrawl(robot, 3));
  REQUIRE(schedule.smoothing_window() == Approx(0.45));
  const double window = schedule.smoothing_window();
  // The average by the midpoint rule, at times from before the first liftoff to after the end.
  for (double t = -0.3; t < schedule.end_time() + 1.0; t += 0.37) {
    constexpr int kSamples = 4000;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int i = 0; i < kSamples; ++i) mean += schedule.FeetCentreXY(t - 0.5 * window + (i + 0.5) * window / kSamples);
    mean /= kSamples;
    INFO("t = " << t);
    CHECK((schedule.NeutralBodyXY(t) - mean).norm() < 1e-6);
  }
  // The feet centre stops and goes: 0.05 m per 0.45 s swing, its velocity v steps at every
  // liftoff and touchdown. The neutral body accelerates at most v over the window and stays
  // within v times an eighth of the window of the feet centre.
  const double dt = 0.025, v = 0.05 / 0.45;
  double feet_peak = 0.0, neutral_peak = 0.0, apart = 0.0;
  for (double t = 0.0; t < schedule.end_time(); t += dt) {
    const auto second = [&](auto f) { return std::abs((f(t + dt) - 2.0 * f(t) + f(t - dt)) / (dt * dt)); };
    feet_peak = std::max(feet_peak, second([&](double s) { return schedule.FeetCentreXY(s).x(); }));
    neutral_peak = std::max(neutral_peak, second([&](double s) { return schedule.NeutralBodyXY(s).x(); }));
    apart = std::max(apart, (schedule.NeutralBodyXY(t) - schedule.FeetCentreXY(t)).norm());
  }
  CHECK(feet_peak > 4.0);
  CHECK(neutral_peak <= v / window * 1.01);
  CHECK(apart <= v * window / 8.0 * 1.01);
  CHECK(apart > 0.5 * v * window / 8.0);
}
