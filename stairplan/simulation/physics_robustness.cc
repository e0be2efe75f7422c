#include "stairplan/simulation/physics_robustness.h"

#include "stairplan/simulation/plan_executor.h"

#include <utility>

namespace stairplan {

PhysicsRobustnessReport EvaluatePhysicsRobustness(const RobotModel& robot, const StairSpec& nominal, const Plan& plan,
                                                  const std::vector<StairSpec>& perturbed, const SimSettings& sim) {
  PhysicsRobustnessReport report;
  report.trials = static_cast<int>(perturbed.size());
  SimSettings answering = sim;
  answering.impact.respond = true;
  SimSettings recording = sim;
  recording.impact.respond = false;
  report.nominal_ok = Simulate(robot, Staircase(nominal), plan, answering).Passed() ? 1 : 0;
  for (const StairSpec& spec : perturbed) {
    const Staircase stairs(spec);
    const SimulationOutcome with = Simulate(robot, stairs, plan, answering);
    report.with_responses_ok += with.Passed() ? 1 : 0;
    report.with_responses_fell += with.status == SimStatus::kFall ? 1 : 0;
    PhysicsRobustnessTrial trial;
    for (const ImpactRecord& e : with.impacts) {
      report.trips += e.kind == ImpactKind::kTrip ? 1 : 0;
      trial.responses += e.executed && e.kind != ImpactKind::kTouchdown ? 1 : 0;
    }
    const SimulationOutcome without = Simulate(robot, stairs, plan, recording);
    report.without_responses_ok += without.Passed() ? 1 : 0;
    report.without_responses_fell += without.status == SimStatus::kFall ? 1 : 0;
    trial.with_responses = with.FirstCause();
    trial.without_responses = without.FirstCause();
    report.runs.push_back(std::move(trial));
  }
  return report;
}

}  // namespace stairplan
