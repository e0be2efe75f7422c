// The trot (GaitChoice::kTrot) executed in MuJoCo, its stance forces from the convex MPC: the
// built-in robot up and down the default stairs in under 8 s, every landing in its step region
// and no link but the feet on the stairs; ANYmal C up them; ANYmal C, Go1 and Go2 up and down
// lower stairs their validators accept.
#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/validation/traversal_validator.h"
#include "stairplan/simulation/plan_executor.h"
#include "executed_cleanly.h"
#include "gait_fixtures.h"
#include "sanitized.h"
#include "shared_robot.h"

using namespace stairplan;

namespace {

// The trot's plan executed: success, every landing touched inside its step region, no other
// contact, the flight (first liftoff to last touchdown) under 8 s; returns the speed along the
// travel [m/s]. `validated`: the validator accepts the plan too.
double TrotsInMuJoCo(const RobotModel& robot, const Staircase& stairs, const std::string& what, bool validated = false) {
  PipelineOptions options;
  options.gait = GaitChoice::kTrot;
  const PipelineResult planned = RunPipeline(robot, stairs, options);
  INFO(what << ": " << planned.plan.status_reason);
  REQUIRE(planned.plan.status == PlanStatus::kOk);
  REQUIRE(planned.plan.gait == Gait::kTrot);
  if (validated) {
    INFO((planned.validation.violations.empty() ? std::string() : ToString(planned.validation.violations.front().kind)));
    CHECK(planned.validation.ok);
  }
  const SimulationOutcome o = Simulate(robot, stairs, planned.plan);
  CHECK(o.stance_forces == StanceForceSource::kConvexMpc);
  CHECK(o.force_qp_failures == 0);
  testing::CheckExecutedCleanly(o, planned.plan, stairs);
  CHECK(FlightDuration(planned.plan) < 8.0);
  return TravelSpeed(planned.plan);
}

}  // namespace

TEST_CASE("the built-in robot trots up and down the default stairs in MuJoCo, a third of a metre a second",
          "[simulation][trot]") {
  const int steps = testing::FullOrSanitized(StairSpec{}.steps, 3);
  for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
    const double speed = TrotsInMuJoCo(BuiltinRobot(), testing::DefaultStairs(direction, steps), direction == TravelDirection::kUp ? "up" : "down");
    CHECK(speed > 0.3);
  }
}

TEST_CASE("ANYmal C trots up the default stairs in MuJoCo", "[simulation][trot]") {
  if (testing::kSanitized) return;  // the built-in robot's trot above runs under the sanitizers
  const std::optional<RobotModel> robot = testing::SharedRobot("anymal_c");
  if (!robot) return;
  CHECK(TrotsInMuJoCo(*robot, testing::DefaultStairs(TravelDirection::kUp), "ANYmal C up") > 0.3);
}

// Issue 19's second acceptance: the same for ANYmal C and two Unitree robots, on stairs their
// validators accept both ways. Their trots are judged on these only: the validator rejects the
// Unitree robots' trots on higher rises (tilts about the diagonal just over its 0.03 rad, or
// wrenches two feet cannot give), and MuJoCo, whose controller corrects what the plan leaves,
// executes most of those too (README).
TEST_CASE("ANYmal C and Unitree Go1 and Go2 trot up and down stairs their validators accept in MuJoCo",
          "[simulation][trot]") {
  if (testing::kSanitized) return;  // the built-in robot's trot above runs under the sanitizers
  struct Case {
    const char* urdf;
    double rise, run;  // [m]
  };
  for (const Case& c : {Case{"anymal_c", 0.08, 0.26}, Case{"unitree_go1", 0.08, 0.26}, Case{"unitree_go2", 0.06, 0.27}}) {
    const std::optional<RobotModel> robot = testing::SharedRobot(c.urdf);
    if (!robot) return;
    for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
      StairSpec spec;
      spec.direction = direction;
      spec.rise = c.rise;
      spec.run = c.run;
      const std::string what = std::string(c.urdf) + (direction == TravelDirection::kUp ? " up" : " down");
      CHECK(TrotsInMuJoCo(*robot, Staircase(spec), what, /*validated=*/true) > 0.3);
    }
  }
}

TEST_CASE("the built-in robot's trot down the default stairs on a friction of 0.2: the validator names the instant "
          "and the leg, and in MuJoCo it slips and falls",
          "[simulation][trot][validation]") {
  if (testing::kSanitized) return;  // the trots above run under the sanitizers
  const Staircase stairs = testing::DefaultStairs(TravelDirection::kDown);
  PipelineOptions options;
  options.gait = GaitChoice::kTrot;
  const PipelineResult planned = RunPipeline(BuiltinRobot(), stairs, options);
  REQUIRE(planned.plan.status == PlanStatus::kOk);
  REQUIRE(planned.validation.ok);  // on the default friction
  const ValidationReport report = testing::ValidateOnFriction(planned.plan, stairs, 0.2);
  REQUIRE_FALSE(report.ok);
  const Violation& first = report.violations.front();
  CAPTURE(first.t, first.leg, ToString(first.kind), first.value);
  CHECK(first.kind == ViolationKind::kFrictionCone);
  CHECK(first.leg_id != LegId::kNone);
  CHECK(first.t > 0.0);
  SimSettings settings;
  settings.world.friction = 0.2;
  const SimulationOutcome o = Simulate(BuiltinRobot(), stairs, planned.plan, settings);
  INFO(ToString(o.status) << " / " << o.FirstCause() << ", slip " << o.max_foot_slip_m << " m (" << o.slipped_leg << ")");
  CHECK_FALSE(o.Passed());
  CHECK(o.status == SimStatus::kFall);
  CHECK(o.max_foot_slip_m > 0.05);
}
