// A plan executed open loop on stairs that moved: the crawl planned for a 27 cm tread steps onto
// one 10 cm shorter, and its feet come down in the collision region before the next riser. Seed
// 000 [0055]'s touchdown is one in the target step location; this one is not, and the foot moves
// into the step region ([0060]) before it takes load.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/impact_detection.h"
#include "stairplan/simulation/plan_executor.h"
#include "sanitized.h"

using namespace stairplan;

TEST_CASE("feet that come down outside the step region of stairs that moved are moved into it, unanswered they stay "
          "outside",
          "[simulation][impact]") {
  const RobotModel& robot = BuiltinRobot();
  StairSpec model;
  model.steps = 2;
  const PipelineOptions options;
  const Plan plan = RunPipeline(robot, Staircase(model), options).plan;
  REQUIRE(plan.status == PlanStatus::kOk);
  StairSpec truth = model;
  truth.runs = {model.run - 0.10};
  const Staircase stairs(truth);

  const SimulationOutcome answered = Simulate(robot, stairs, plan, SimSettings{});
  INFO("with responses: " << answered.FirstCause());
  CHECK(answered.Passed());
  CHECK(answered.landings.size() == plan.footsteps.size());
  int moved = 0;
  for (const ImpactRecord& e : answered.impacts) {
    if (e.kind != ImpactKind::kMisplacedTouchdown) continue;
    INFO(e.leg << " at t=" << e.t << ": " << e.reason);
    ++moved;
    CHECK(e.response == ResponseKind::kAdjustStep);
    CHECK(e.executed);
    CHECK((e.target_W - e.at_W).head<2>().norm() < 0.06);  // a short hop, not a new step
    CHECK(e.target_W.x() < e.at_W.x());                    // back from the riser that came closer
  }
  CHECK(moved == 4);  // every foot's step onto the shortened tread: two front, two hind

  if (testing::kSanitized) return;  // the unanswered run only in the normal build: it adds no code path
  SimSettings off;
  off.impact.respond = false;
  const SimulationOutcome unanswered = Simulate(robot, stairs, plan, off);
  INFO("without responses: " << unanswered.FirstCause());
  CHECK_FALSE(unanswered.Passed());
  CHECK_FALSE(unanswered.AllLandedInRegions());
  CHECK(std::count_if(unanswered.impacts.begin(), unanswered.impacts.end(),
                      [](const ImpactRecord& e) { return e.kind == ImpactKind::kMisplacedTouchdown && !e.executed; }) == 4);
}
