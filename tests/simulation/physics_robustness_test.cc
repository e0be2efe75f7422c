// Acceptance 3 of issue #26 in small: the robustness command's perturbation (sigma run 3 cm,
// rise 1 cm) on a short flight, the nominal plan executed open loop with and without the impact
// responses. The full count (`stairplan robustness --simulate`, 20 staircases of 7 steps) is too
// long for a unit test; this keeps its direction.
#include <catch2/catch.hpp>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/pipeline/robustness.h"
#include "stairplan/simulation/physics_robustness.h"
#include "sanitized.h"

using namespace stairplan;

TEST_CASE("on perturbed stairs the open-loop plan passes more often answering impacts than only recording them",
          "[simulation][impact]") {
  if (testing::kSanitized) return;  // five MuJoCo runs of a flight: a minute under the sanitizers
  const RobotModel& robot = BuiltinRobot();
  StairSpec nominal;
  nominal.steps = 3;
  const PipelineOptions options;
  const Plan plan = RunPipeline(robot, Staircase(nominal), options).plan;
  REQUIRE(plan.status == PlanStatus::kOk);
  RobustnessSettings perturbation;
  perturbation.sigma_run = 0.03;
  perturbation.sigma_rise = 0.01;
  perturbation.trials = 2;  // the second's treads move its feet out of the step regions
  const PhysicsRobustnessReport report =
      EvaluatePhysicsRobustness(robot, nominal, plan, PerturbedStaircases(nominal, perturbation));
  std::string runs;
  for (const PhysicsRobustnessTrial& run : report.runs) runs += "\n  with: " + run.with_responses + " / without: " + run.without_responses;
  INFO("with " << report.with_responses_ok << ", without " << report.without_responses_ok << runs);
  CHECK(report.nominal_ok == 1);
  REQUIRE(report.runs.size() == 2u);
  CHECK(report.with_responses_ok > report.without_responses_ok);
  CHECK(report.with_responses_fell <= report.without_responses_fell);
}
