// The robustness command's perturbed stairs in MuJoCo: the nominal plan executed open loop on each
// staircase, once answering impacts and once only recording them, so that what the responses of
// US 2020/0324412 [0053]-[0068] buy is counted on the same stairs.
#pragma once

#include <string>
#include <vector>

#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"
#include "stairplan/simulation/sim_settings.h"

namespace stairplan {

/// One perturbed staircase's two runs: why each failed ("" when it passed, SimulationOutcome::FirstCause).
struct PhysicsRobustnessTrial {
  std::string with_responses;     ///< the run answering impacts
  std::string without_responses;  ///< the run only recording them
  int responses = 0;  ///< responses carried out in the run with them (touchdowns not counted)
};

/// How a plan fared in MuJoCo on perturbed stairs, with and without the impact responses.
struct PhysicsRobustnessReport {
  int trials = 0;  ///< perturbed staircases run
  int nominal_ok = 0;            ///< 1 when the plan passes in MuJoCo on the stairs it was planned for
  int with_responses_ok = 0;     ///< perturbed staircases where the run passed answering impacts
  int without_responses_ok = 0;  ///< ... where it passed with impacts only recorded
  ///@{
  /// Runs that fell (SimStatus::kFall) with and without responses. A run that stays up can still
  /// fail Passed(): the open-loop plan's own footholds may lie outside the moved treads' regions.
  int with_responses_fell = 0;
  int without_responses_fell = 0;
  ///@}
  int trips = 0;                 ///< trips detected over the runs with responses
  std::vector<PhysicsRobustnessTrial> runs;  ///< per perturbed staircase, in order
};

/// Executes `plan` (planned on `nominal`) on each of `perturbed` (the robustness command's
/// PerturbedStaircases) with `sim`'s impact detection, with and without responses. A run passes
/// when SimulationOutcome::Passed().
PhysicsRobustnessReport EvaluatePhysicsRobustness(const RobotModel& robot, const StairSpec& nominal, const Plan& plan,
                                                  const std::vector<StairSpec>& perturbed, const SimSettings& sim = {});

}  // namespace stairplan
