// The per-cycle update allocates nothing after construction (DESIGN.md: hot paths never allocate).
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/step_planner.h"

using namespace stairplan;

TEST_CASE("StepPlanner::Update allocates nothing, cycle after cycle", "[step][alloc]") {
  for (TravelDirection d : {TravelDirection::kUp, TravelDirection::kDown}) {
    StairSpec spec;
    spec.direction = d;
    const Staircase stairs(spec);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    StepPlanner planner(BuiltinRobot(), map);
    StepPlannerInput in;
    in.velocity_W = {0.15, 0.0};
    in.body_xy_W = {-0.8, 0.0};
    for (int l = 0; l < 4; ++l) {
      const Eigen::Vector2d p = planner.SnapIntoRegion(0, planner.NeutralFootXY(l, in.body_xy_W));
      in.legs[static_cast<std::size_t>(l)].foot_W = {p.x(), p.y(), map.stair(0).z};
      in.legs[static_cast<std::size_t>(l)].stair = 0;
    }
    int selections = 0;
    stairplan::testing::AllocationScope scope;
    // Walk the whole flight, committing the chosen controller's first footstep each cycle.
    for (int cycle = 0; cycle < 60; ++cycle) {
      const int chosen = planner.Update(in);
      if (chosen < 0) break;
      ++selections;
      // Commit the chosen plan's first phase (one leg in a crawl, two in a trot).
      const ControllerEvaluation& e = planner.evaluation(chosen);
      for (int k = 0; k < e.step_count && e.steps[static_cast<std::size_t>(k)].t_liftoff <= in.now_s; ++k) {
        const PlannedStep& s = e.steps[static_cast<std::size_t>(k)];
        auto& leg = in.legs[static_cast<std::size_t>(s.leg)];
        leg.foot_W = s.target_W;
        leg.stair = s.target_stair;
        leg.last_touchdown_s = s.t_touchdown;
      }
      const double T = planner.controllers()[static_cast<std::size_t>(chosen)].cadence_s;
      in.now_s += T;
      in.body_xy_W.x() += in.velocity_W.x() * T;
    }
    CHECK(scope.count() == 0);
    CHECK(selections == 60);
  }
}
