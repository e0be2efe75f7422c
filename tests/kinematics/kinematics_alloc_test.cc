// FK, Jacobian, link frames and IK allocate nothing once the workspace exists.
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"

TEST_CASE("leg kinematics queries allocate nothing after warm-up", "[alloc][leg_kinematics]") {
  const stairplan::RobotKinematics kinematics(stairplan::BuiltinRobot());
  stairplan::RobotWorkspace ws(kinematics);
  const auto& leg = kinematics.leg(0);
  auto& lws = ws.leg(0);
  const Eigen::Vector3d q(0.1, 0.6, -1.2);
  const Eigen::Vector3d target = leg.FootPosition(q, lws);
  const Eigen::Vector3d far = leg.hip_B() + Eigen::Vector3d(0, 0, -2);
  stairplan::testing::AllocationScope scope;
  double sink = 0.0;
  sink += leg.FootPosition(q, lws).sum();
  sink += leg.KneePosition(q, lws).sum();
  sink += leg.FootJacobian(q, lws).sum();
  sink += leg.LinkFrames(q, lws).back().translation().sum();
  sink += leg.SolveFootIk(target, lws).error;
  sink += leg.SolveFootIk(far, lws).error;  // the failing path: restarts and the unconstrained solve
  stairplan::BodyPose body;
  sink += kinematics.SolveFootIkWorld(0, target, body, ws).error;
  CHECK(scope.count() == 0);
  CHECK(sink != 0.0);
}
