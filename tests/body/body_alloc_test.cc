// The control loop allocates nothing: Update cycles after warm-up, counted, with and without leg rows.
#include <catch2/catch.hpp>

#include <cstddef>
#include <utility>

#include "alloc_counter.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/crawl_planner.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

// Allocations in `cycles` Update cycles `period` apart after a warm-up pass over the same cycles
// (which fills the planner's caches for exactly this trajectory), and how many QPs they solved.
std::pair<std::size_t, int> CountAllocations(const BodyPlannerSettings& given, double period, int cycles) {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  // The default crawl: its legs graze and penetrate stairs in some of the planner's candidate
  // postures, which is where FCL's contact computation used to allocate (stairplan/collision/signed_distance.cc).
  const Plan footsteps = PlanCrawl(robot, stairs, map);
  REQUIRE(footsteps.status == PlanStatus::kOk);
  BodyPlannerSettings settings = given;
  settings.cycle_budget_s = 1.0;  // every cycle solves (the timing of this machine must not matter)
  BodyPlanner planner(robot, stairs, map, footsteps, settings);
  // Start on the flight's first steps, where the bounds are active.
  const double start = 2.0;
  const auto run = [&] {
    planner.Reset();
    BodyState state = planner.Interpolate(start);
    planner.Update(state, BodyCommand{}, start);  // warm-up solves
    int solved = 0;
    testing::AllocationScope scope;
    for (int c = 1; c <= cycles; ++c) {
      const double now = start + c * period;
      state = planner.Interpolate(now);
      const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
      solved += out.solves;
    }
    return std::make_pair(scope.count(), solved);
  };
  run();
  return run();
}

}  // namespace

TEST_CASE("1,000 Update cycles after warm-up allocate nothing", "[body][alloc]") {
  // Under the sanitizers 100 cycles (each solve is ~20x slower there); still after the warm-up pass.
  constexpr int kCycles = testing::FullOrSanitized(1000, 100);
  const auto [allocations, solved] = CountAllocations(BodyPlannerSettings{}, 0.003, kCycles);
  CHECK(solved >= kCycles);  // every cycle solved (a rare cold retry adds one)
  CHECK(allocations == 0);
}

TEST_CASE("with leg rows, Update cycles after warm-up allocate nothing, rows carried across cycles or not",
          "[body][alloc][stance_rows]") {
  // Not under the sanitizers, where its four warm-ups of 60 leg-row solves took most of two minutes:
  // the leg rows' code runs there in "over a climb the rows carried across cycles ..." and "with
  // stance rows the body QP keeps every stance leg ...". What this test counts is the normal build's.
  if (testing::kSanitized) return;
  // KDL, FCL and the exact COM every knot: 4 ms a cycle, so 200 cycles.
  constexpr int kCycles = 200;
  BodyPlannerSettings settings;
  settings.stance_rows = true;
  settings.stability_margin = 0.03;
  // At the knot spacing the rows of the last cycle are taken over (KnotRowCache); at 3 ms never.
  for (const double period : {settings.knot_dt, 0.003}) {
    INFO("period " << period << " s");
    const auto [allocations, solved] = CountAllocations(settings, period, kCycles);
    CHECK(solved >= kCycles);
    CHECK(allocations == 0);
  }
}
