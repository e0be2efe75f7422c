// Acceptance property: over 1,000 random staircases within building-code ranges (fixed seed),
// every target of the chosen plan lies inside its step region and within reach of its leg, from
// touchdown until the leg lifts it again.
#include <catch2/catch.hpp>

#include <random>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/step_planner_driver.h"
#include "sanitized.h"
#include "step_test_util.h"

using namespace stairplan;

TEST_CASE("1000 random code-range staircases: targets in step regions and in reach", "[step][property]") {
  std::mt19937 rng(20261122);
  // Residential and commercial codes: rise 102-196 mm, going 254-356 mm, nosing 0-32 mm, at most
  // 9.5 mm variation within a flight (every third staircase is irregular); a few stairs to a long
  // flight, both directions, both facings.
  std::uniform_real_distribution<double> rise(0.102, 0.196), run(0.254, 0.356), nosing(0.0, 0.032),
      variation(-0.00475, 0.00475);
  std::uniform_int_distribution<int> steps(2, 16), coin(0, 1);
  const RobotModel& robot = BuiltinRobot();
  const StepPlannerSettings settings;
  // The first 100 of the same sequence under the sanitizers, where all 1,000 take minutes.
  const int cases = stairplan::testing::FullOrSanitized(1000, 100);
  int ok = 0, footsteps = 0;
  for (int i = 0; i < cases; ++i) {
    StairSpec spec;
    spec.steps = steps(rng);
    spec.rise = rise(rng);
    spec.run = run(rng);
    spec.nosing = nosing(rng);
    spec.direction = coin(rng) ? TravelDirection::kUp : TravelDirection::kDown;
    if (i % 3 == 2) {
      for (int k = 0; k < spec.steps; ++k) spec.rises.push_back(std::min(0.196, spec.rise + variation(rng)));
      for (int k = 0; k + 1 < spec.steps; ++k) spec.runs.push_back(std::max(0.254, spec.run + variation(rng)));
    }
    const Facing facing = coin(rng) ? Facing::kForward : Facing::kBackward;
    const Staircase stairs(spec);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, facing);
    const Plan plan = PlanWithStepPlanner(robot, stairs, map, settings);
    INFO("case " << i << ": steps " << spec.steps << " rise " << spec.rise << " run " << spec.run << " nosing "
                 << spec.nosing << " " << ToString(spec.direction) << " facing " << ToString(facing) << ": "
                 << plan.status_reason);
    CHECK(plan.status == PlanStatus::kOk);
    ok += plan.status == PlanStatus::kOk ? 1 : 0;
    for (const Footstep& f : plan.footsteps) {
      ++footsteps;
      if (!map.InStepRegion(f.stair_index, f.position_W.head<2>())) FAIL_CHECK("footstep outside its step region: " << f.leg << " at t " << f.t_touchdown);
      const double e = stairplan::testing::Extension(robot, plan, f, f.t_touchdown);
      if (e > settings.reach_max_fraction + 1e-6 || e < settings.reach_min_fraction - 1e-6) {
        FAIL_CHECK("footstep out of reach: " << f.leg << " at t " << f.t_touchdown << " extension " << e);
      }
      const double lift = stairplan::testing::LiftoffAfter(plan, f);
      const double e_lift = stairplan::testing::Extension(robot, plan, f, lift);
      if (e_lift > settings.reach_max_fraction + 1e-6) {
        FAIL_CHECK("foot out of reach before liftoff: " << f.leg << " at t " << lift << " extension " << e_lift);
      }
    }
  }
  CHECK(ok == cases);
  CHECK(footsteps > 20 * cases);
}
