// The walk (PipelineOptions::gait) executed in MuJoCo: where the validator's dynamic check has passed
// its quicker weight shifts, physics carries the robot through them.
#include <catch2/catch.hpp>

#include <optional>
#include <string>
#include <vector>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/plan_executor.h"
#include "executed_cleanly.h"
#include "gait_fixtures.h"
#include "sanitized.h"
#include "shared_robot.h"

using namespace stairplan;

namespace {

// The walk's plan validates, and MuJoCo executes it at its own pace: success, every landing
// touched inside its step region, no link but the feet on the stairs.
void WalksInMuJoCo(const RobotModel& robot, const Staircase& stairs, const std::string& what) {
  PipelineOptions options;
  options.gait = GaitChoice::kWalk;
  const PipelineResult planned = RunPipeline(robot, stairs, options);
  INFO(what << ": " << planned.plan.status_reason);
  REQUIRE(planned.validation.ok);
  REQUIRE(planned.plan.gait == Gait::kWalk);
  testing::CheckExecutedCleanly(Simulate(robot, stairs, planned.plan), planned.plan, stairs);
}

}  // namespace

TEST_CASE("the built-in robot walks up the default stairs in MuJoCo at the walk's pace", "[simulation][walk]") {
  const int steps = testing::FullOrSanitized(StairSpec{}.steps, 3);
  WalksInMuJoCo(BuiltinRobot(), testing::DefaultStairs(TravelDirection::kUp, steps), "stairbot up");
}

TEST_CASE("ANYmal C walks up and down the default stairs in MuJoCo at the walk's pace", "[simulation][walk]") {
  if (testing::kSanitized) return;  // the built-in robot's walk above runs under the sanitizers
  const std::optional<RobotModel> robot = testing::SharedRobot("anymal_c");
  if (!robot) return;
  for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
    WalksInMuJoCo(*robot, testing::DefaultStairs(direction), direction == TravelDirection::kUp ? "up" : "down");
  }
}
