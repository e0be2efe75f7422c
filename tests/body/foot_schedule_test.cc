// The feet's timeline read from a footstep plan: stances, swings, the neutral body and the slope.
#include <catch2/catch.hpp>

#include "kinematics/builtin_robot.h"
#include <limits>

#include "planning/body/foot_schedule.h"

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

TEST_CASE("the neutral body sits over the feet and the feet's slope is their pitch", "[body][schedule]") {
  const RobotModel& robot = BuiltinRobot();
  const Plan plan = OneStep(robot);
  const FootSchedule schedule(robot, plan);
  CHECK(schedule.NeutralBodyXY(0.0).norm() < 1e-12);
  // After the step the LF foot is 0.2 m ahead: the body moves a quarter of it.
  CHECK(schedule.NeutralBodyXY(2.0).x() == Approx(0.05));
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
