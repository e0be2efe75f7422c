// The step-height rule over a whole flight (stairplan/planning/step/step_height.h): the first rise higher
// than the lowest-stepping leg can step is found, up and down, wherever it is in the flight, and
// the offline driver refuses such a flight before its first cycle, naming that rise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/step_height.h"
#include "stairplan/planning/step/step_planner_driver.h"

using namespace stairplan;

namespace {

double LowestStep(const std::vector<LegModel>& legs, const StepPlannerSettings& settings) {
  double lowest = MaxStepHeight(legs.front(), settings);
  for (const LegModel& leg : legs) lowest = std::min(lowest, MaxStepHeight(leg, settings));
  return lowest;
}

// Seven rises a little under `step`, the one at `tall` (1-based riser) `excess` above it.
Staircase FlightWithTallRise(double step, int tall, double excess, TravelDirection direction) {
  StairSpec spec;
  spec.direction = direction;
  spec.rises.assign(static_cast<std::size_t>(spec.steps), 0.9 * step);
  spec.rises[static_cast<std::size_t>(tall - 1)] = step + excess;
  return Staircase(spec);
}

}  // namespace

TEST_CASE("A leg's highest step is the settings' share of its reach", "[step][step_height]") {
  const RobotModel robot = BuiltinRobot();
  StepPlannerSettings settings;
  for (const LegModel& leg : robot.legs()) {
    CHECK(MaxStepHeight(leg, settings) == Approx(0.45 * leg.max_reach));
  }
  settings.max_step_height_fraction = 0.3;
  CHECK(MaxStepHeight(robot.legs().front(), settings) == Approx(0.3 * robot.legs().front().max_reach));
}

TEST_CASE("The first rise no leg can step is found wherever it is, up and down", "[step][step_height]") {
  const RobotModel robot = BuiltinRobot();
  const StepPlannerSettings settings;
  const double step = LowestStep(robot.legs(), settings);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> riser(1, 7);
  for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
    for (int trial = 0; trial < 10; ++trial) {
      const int tall = riser(rng);
      const Staircase stairs = FlightWithTallRise(step, tall, 0.002, direction);
      const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
      const auto found = FirstRiseTooHigh(robot.legs(), map, settings);
      INFO(ToString(direction) << ", riser " << tall);
      REQUIRE(found);
      // Rises are in travel order: riser k leads onto surface k either way.
      CHECK(found->surface == tall);
      CHECK(found->rise == Approx(step + 0.002));
      CHECK(found->max_step == Approx(step));
      CHECK(found->rise > found->max_step);
      // 1 mm under the step, the same flight passes.
      const Staircase lower = FlightWithTallRise(step, tall, -0.001, direction);
      CHECK_FALSE(FirstRiseTooHigh(robot.legs(), ConstrainedMap::FromStaircase(lower, Facing::kForward), settings));
    }
  }
}

TEST_CASE("The leg named is the one with the lowest step", "[step][step_height]") {
  std::vector<LegModel> legs = BuiltinRobot().legs();
  legs[2].max_reach *= 0.8;
  const StepPlannerSettings settings;
  const double step = MaxStepHeight(legs[2], settings);
  const Staircase stairs = FlightWithTallRise(step, 3, 0.001, TravelDirection::kUp);
  const auto found = FirstRiseTooHigh(legs, ConstrainedMap::FromStaircase(stairs, Facing::kForward), settings);
  REQUIRE(found);
  CHECK(found->leg == legs[2].name);
  CHECK(found->max_reach == Approx(legs[2].max_reach));
  CHECK_THAT(ToString(*found), Catch::Contains("surface 3") && Catch::Contains(legs[2].name) &&
                                   Catch::Contains("step height"));
}

TEST_CASE("The driver refuses a flight with a rise no leg can step, before any footstep", "[step][step_height]") {
  const RobotModel robot = BuiltinRobot();
  const StepPlannerSettings settings;
  const double step = LowestStep(robot.legs(), settings);
  const Staircase stairs = FlightWithTallRise(step, 5, 0.01, TravelDirection::kUp);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const Plan plan = PlanWithStepPlanner(robot, stairs, map, settings);
  CHECK(plan.status == PlanStatus::kInfeasible);
  CHECK(plan.status_reason == ToString(*FirstRiseTooHigh(robot.legs(), map, settings)));
  CHECK(plan.footsteps.empty());
  CHECK(plan.selected == -1);
}
