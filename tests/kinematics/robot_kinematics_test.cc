// Whole-robot kinematics: IK for world targets under a body pose, reachable body heights.
#include <catch2/catch.hpp>

#include <optional>
#include <random>
#include <string>
#include <vector>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "shared_robot.h"

using stairplan::BodyPose;
using stairplan::RobotKinematics;
using stairplan::RobotWorkspace;

TEST_CASE("world IK undoes the body pose", "[robot_kinematics]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  RobotWorkspace ws(kinematics);
  BodyPose body;
  body.position_W = {1.0, 0.2, 0.5};
  body.pitch = -0.3;
  body.yaw = 0.4;
  const Eigen::Vector3d q(0.1, 0.5, -1.1);
  const int lh = kinematics.LegIndex("LH");
  const Eigen::Vector3d foot_W = body.ToIsometry() * kinematics.leg(lh).FootPosition(q, ws.leg(lh));
  const auto result = kinematics.SolveFootIkWorld(lh, foot_W, body, ws);
  REQUIRE(result.ok());
  CHECK((body.ToIsometry() * kinematics.leg(lh).FootPosition(result.q, ws.leg(lh)) - foot_W).norm() < 1e-9);
  // Nose-up is negative pitch: the front of the body rises.
  CHECK((body.ToIsometry() * Eigen::Vector3d(1, 0, 0)).z() > body.position_W.z());
}

TEST_CASE("reachable body heights bracket the leg's vertical reach", "[robot_kinematics]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  RobotWorkspace ws(kinematics);
  const int lf = kinematics.LegIndex("LF");
  const auto& leg = kinematics.leg(lf);
  BodyPose body;
  body.position_W = {0.0, 0.0, 0.5};
  // Foot straight under the hip, at the foot's lateral offset.
  const Eigen::Vector3d foot_W(leg.hip_B().x(), leg.model().foot_zero_B.y(), 0.0);
  const auto heights = kinematics.ReachableBodyHeights(lf, foot_W, body, ws);
  REQUIRE_FALSE(heights.empty());
  // Highest: hip 0.6 m above the foot with the knee at its -0.35 limit: 2 * 0.3 * cos(0.175).
  CHECK(heights.hi == Approx(0.60 * std::cos(0.175)).margin(2e-4));
  CHECK(heights.lo < 0.25);
  body.position_W.z() = 0.5 * (heights.lo + heights.hi);
  CHECK(kinematics.SolveFootIkWorld(lf, foot_W, body, ws).ok());
  body.position_W.z() = heights.hi + 0.01;
  CHECK_FALSE(kinematics.SolveFootIkWorld(lf, foot_W, body, ws).ok());
}

TEST_CASE("a copy of a robot's kinematics answers as a fresh build does, after the original is gone",
          "[robot_kinematics]") {
  // The pipeline builds a robot's kinematics once and the reach model, the body planner and the
  // validator copy them: a copy must not lean on the object it was copied from.
  std::vector<stairplan::RobotModel> robots = {stairplan::BuiltinRobot()};
  for (const std::string name : {"anymal_c", "unitree_go2"}) {
    if (const std::optional<stairplan::RobotModel> robot = stairplan::testing::SharedRobot(name)) robots.push_back(*robot);
  }
  for (const stairplan::RobotModel& robot : robots) {
    INFO(robot.name());
    std::optional<RobotKinematics> original(std::in_place, robot);
    const RobotKinematics copy = *original;
    original.reset();
    const RobotKinematics fresh(robot);
    RobotWorkspace ws_copy(copy), ws_fresh(fresh);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int l = 0; l < fresh.leg_count(); ++l) {
      const auto& a = copy.leg(l);
      const auto& b = fresh.leg(l);
      CHECK(a.nominal() == b.nominal());
      CHECK(a.reach().lo == b.reach().lo);
      CHECK(a.reach().hi == b.reach().hi);
      for (int i = 0; i < 50; ++i) {
        Eigen::Vector3d q;
        for (int j = 0; j < 3; ++j) q(j) = b.lower()(j) + unit(random) * (b.upper()(j) - b.lower()(j));
        const Eigen::Vector3d foot = b.FootPosition(q, ws_fresh.leg(l));
        CHECK(a.FootPosition(q, ws_copy.leg(l)) == foot);
        CHECK(a.FootJacobian(q, ws_copy.leg(l)) == b.FootJacobian(q, ws_fresh.leg(l)));
        const stairplan::IkResult ik_a = a.SolveFootIk(foot, ws_copy.leg(l));
        const stairplan::IkResult ik_b = b.SolveFootIk(foot, ws_fresh.leg(l));
        CHECK(ik_a.status == ik_b.status);
        CHECK(ik_a.q == ik_b.q);
      }
    }
  }
}
