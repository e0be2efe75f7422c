// The control loop allocates nothing: 1,000 Update cycles after warm-up, counted.
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "kinematics/builtin_robot.h"
#include "planning/body/body_planner.h"
#include "planning/crawl_planner.h"
#include "sanitized.h"

using namespace stairplan;

TEST_CASE("1,000 Update cycles after warm-up allocate nothing", "[body][alloc]") {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  // The default crawl: its legs graze and penetrate stairs in some of the planner's candidate
  // postures, which is where FCL's contact computation used to allocate (collision/signed_distance.cc).
  const Plan footsteps = PlanCrawl(robot, stairs, map);
  REQUIRE(footsteps.status == PlanStatus::kOk);
  BodyPlannerSettings settings;
  settings.cycle_budget_s = 1.0;  // every cycle solves (the timing of this machine must not matter)
  BodyPlanner planner(robot, stairs, map, footsteps, settings);
  constexpr double kPeriod = 0.003;
  // Under the sanitizers 100 cycles (each solve is ~20x slower there); still after the warm-up pass.
  constexpr int kCycles = testing::FullOrSanitized(1000, 100);
  // Start on the flight's first steps, where the bounds are active. The first pass is the
  // warm-up: it fills the planner's caches for exactly this trajectory.
  const double start = 2.0;
  const auto run = [&](int cycles) {
    planner.Reset();
    BodyState state = planner.Interpolate(start);
    planner.Update(state, BodyCommand{}, start);  // warm-up solves
    int solved = 0;
    testing::AllocationScope scope;
    for (int c = 1; c <= cycles; ++c) {
      const double now = start + c * kPeriod;
      state = planner.Interpolate(now);
      const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
      solved += out.solves;
    }
    return std::make_pair(scope.count(), solved);
  };
  run(kCycles);
  const auto [allocations, solved] = run(kCycles);
  CHECK(solved >= kCycles);  // every cycle solved (a rare cold retry adds one)
  CHECK(allocations == 0);
}
