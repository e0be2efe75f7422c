// CrowdedTouchdowns: a touchdown on a foothold another foot still stands on, seen from above.
#include <catch2/catch.hpp>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/crawl_planner.h"

using namespace stairplan;

namespace {

// The built-in robot standing on a rectangle, its feet `length` apart along x and 0.3 m across.
Plan Standing(const RobotModel& robot, double length) {
  Plan plan;
  for (const LegModel& leg : robot.legs()) {
    plan.legs.push_back(leg.name);
    const double x = leg.hip_B.x() > 0.0 ? 0.5 * length : -0.5 * length;
    plan.initial_feet_W.emplace_back(x, leg.hip_B.y() > 0.0 ? 0.15 : -0.15, 0.0);
  }
  return plan;
}

Footstep Step(const std::string& leg, double t, const Eigen::Vector3d& at) {
  Footstep step;
  step.leg = leg;
  step.t_liftoff = t - 0.4;
  step.t_touchdown = t;
  step.position_W = at;
  return step;
}

}  // namespace

TEST_CASE("a touchdown counts as crowded when its foot overlaps a standing foot, not when it clears it or that foot has left",
          "[planning][crawl]") {
  const RobotModel robot = BuiltinRobot();
  double radii = 0.0;  // the right legs' foot radii together
  for (const LegModel& leg : robot.legs()) radii += leg.name == "RF" || leg.name == "RH" ? leg.foot_radius : 0.0;
  REQUIRE(radii > 0.0);
  Plan plan = Standing(robot, 0.4);
  const Eigen::Vector3d rf(0.2, -0.15, 0.0);
  // RH lands just clear of RF, then RF steps on, then RH lands where RF stood: no overlap yet.
  plan.footsteps = {Step("RH", 1.0, rf - Eigen::Vector3d(radii + 1e-3, 0.0, 0.0)), Step("RF", 2.0, rf + Eigen::Vector3d(0.3, 0.0, 0.0)),
                    Step("RH", 3.0, rf)};
  CHECK(CrowdedTouchdowns(robot, plan).touchdowns == 0);
  // RH lands overlapping RF (a millimetre short of clearing it), then LH lands on LF itself.
  plan.footsteps = {Step("RH", 1.0, rf - Eigen::Vector3d(radii - 1e-3, 0.0, 0.0)), Step("LH", 2.0, Eigen::Vector3d(0.2, 0.15, 0.0))};
  const TouchdownCrowding crowding = CrowdedTouchdowns(robot, plan);
  CHECK(crowding.touchdowns == 2);
  CHECK(crowding.first_t == 1.0);
  CHECK(crowding.leg == "RH");
  CHECK(crowding.onto == "RF");
}
