// The reach models (geometric, IK) and the ground profile the step planner's body follows.
#include <catch2/catch.hpp>

#include <random>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/ground_profile.h"
#include "stairplan/planning/step/ik_reach_model.h"
#include "stairplan/planning/step/reach_model.h"
#include "stairplan/planning/step/step_planner_driver.h"
#include "step_test_util.h"

using namespace stairplan;

TEST_CASE("geometric reach: the band of hip-to-foot distances", "[step]") {
  const LegModel& leg = BuiltinRobot().leg("LF");
  const GeometricReachModel model(0.3, 0.95);
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.translation() = Eigen::Vector3d(1.0, 0.5, 0.6);
  const Eigen::Vector3d hip = base * leg.hip_B;
  for (double f : {0.31, 0.5, 0.94}) CHECK(model.Reachable(leg, base, hip - Eigen::Vector3d(0, 0, f * leg.max_reach)));
  for (double f : {0.0, 0.29, 0.96, 2.0}) CHECK_FALSE(model.Reachable(leg, base, hip - Eigen::Vector3d(0, 0, f * leg.max_reach)));
  // Effort: 0 mid-band, 1 at the ends.
  CHECK(model.Effort(leg, base, hip - Eigen::Vector3d(0, 0, 0.625 * leg.max_reach)) == Approx(0.0).margin(1e-12));
  CHECK(model.Effort(leg, base, hip - Eigen::Vector3d(0, 0, 0.95 * leg.max_reach)) == Approx(1.0));
  // The hip moves with the base's rotation.
  base.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d hip_rotated = base * leg.hip_B;
  CHECK(hip_rotated.x() == Approx(1.0 - leg.hip_B.x()));
  CHECK(model.Reachable(leg, base, hip_rotated - Eigen::Vector3d(0, 0, 0.5 * leg.max_reach)));
  CHECK_THROWS_AS(GeometricReachModel(0.5, 0.4), std::invalid_argument);
  CHECK_THROWS_AS(GeometricReachModel(-0.1, 0.9), std::invalid_argument);
}

TEST_CASE("ground profile: through the tread middles, flat on the landings, continuous", "[step]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> rise(0.10, 0.22), run(0.20, 0.35);
  for (int i = 0; i < 50; ++i) {
    StairSpec spec;
    spec.rise = rise(rng);
    spec.run = run(rng);
    spec.direction = i % 2 ? TravelDirection::kDown : TravelDirection::kUp;
    const Staircase stairs(spec);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    const GroundProfile g = GroundProfile::FromMap(map);
    for (int k = 1; k < stairs.steps(); ++k) {
      const StairSurface& s = stairs.surface(k);
      CHECK(g.HeightAt(0.5 * (s.x_begin + s.x_end)) == Approx(s.z).margin(1e-12));
      // Within a tread the line stays within one rise of the tread.
      CHECK(std::abs(g.HeightAt(s.x_begin) - s.z) <= spec.rise + 1e-9);
    }
    CHECK(g.HeightAt(stairs.x_min()) == Approx(stairs.surface(0).z));
    CHECK(g.HeightAt(stairs.x_max() + 5.0) == Approx(stairs.surface(stairs.steps()).z));
    for (double x = stairs.x_min(); x < stairs.x_max(); x += 0.01) {
      CHECK(std::abs(g.HeightAt(x + 0.01) - g.HeightAt(x)) <= 0.01 * std::tan(1.2) + 1e-9);
    }
  }
}

TEST_CASE("IK reach: agrees with the kinematics and is stricter than the geometric band", "[step]") {
  const RobotModel& robot = BuiltinRobot();
  const IkReachModel ik(robot);
  const GeometricReachModel band(0.0, 1.0);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> offset(-0.8, 0.8), pitch(-0.5, 0.5);
  int reachable = 0, unreachable = 0;
  for (int i = 0; i < 400; ++i) {
    Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
    base.linear() = Eigen::AngleAxisd(pitch(rng), Eigen::Vector3d::UnitY()).toRotationMatrix();
    base.translation() = Eigen::Vector3d(0.2, 0.0, 0.5);
    const LegModel& leg = robot.legs()[static_cast<std::size_t>(i % 4)];
    const Eigen::Vector3d foot = base * leg.hip_B + Eigen::Vector3d(offset(rng), 0.5 * offset(rng), -std::abs(offset(rng)));
    const bool ok = ik.Reachable(leg, base, foot);
    // Whatever the IK reaches lies within the chain's length.
    if (ok) CHECK(band.Reachable(leg, base, foot));
    (ok ? reachable : unreachable) += 1;
  }
  // Both verdicts occur: the test samples both sides of the boundary.
  CHECK(reachable > 20);
  CHECK(unreachable > 20);
}

TEST_CASE("IK reach plugs into the offline driver: every touchdown solves within the joint limits", "[step]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  auto ik = std::make_shared<IkReachModel>(BuiltinRobot());
  const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map, {}, ik);
  INFO(plan.status_reason);
  REQUIRE(plan.status == PlanStatus::kOk);
  RobotWorkspace ws(ik->kinematics());
  for (const Footstep& f : plan.footsteps) {
    const stairplan::BodyState b = stairplan::testing::BodyAt(plan, f.t_touchdown);
    BodyPose pose;
    pose.position_W = {b.x, b.y, b.z};
    pose.pitch = b.pitch;
    pose.yaw = b.yaw;
    const int index = ik->kinematics().LegIndex(f.leg);
    const Eigen::Vector3d centre = f.position_W + Eigen::Vector3d(0.0, 0.0, BuiltinRobot().leg(f.leg).foot_radius);
    CAPTURE(f.leg, f.t_touchdown);
    CHECK(ik->kinematics().SolveFootIkWorld(index, centre, pose, ws).ok());
  }
}
