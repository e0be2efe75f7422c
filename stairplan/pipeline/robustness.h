// Open-loop robustness to stair errors (the 2012 paper's dW/dH analysis): a plan made for the
// nominal stairs is executed on stairs whose every rise and run is off by a random error, and
// compared with replanning on the true stairs. A foot lands where the true surface is under the
// planned foothold; the body follows its nominal reference.
#pragma once

#include <cstdint>
#include <vector>

#include "stairplan/kinematics/robot_model.h"
#include "stairplan/pipeline/plan_pipeline.h"

namespace stairplan {

/// How EvaluateRobustness() perturbs the stairs: per-step Gaussian errors of rise and run.
struct RobustnessSettings {
  double sigma_rise = 0.005;  ///< standard deviation of each rise's error [m]
  double sigma_run = 0.01;    ///< standard deviation of each run's error [m]
  int trials = 20;  ///< perturbed staircases drawn
  std::uint32_t seed = 1;  ///< random seed: the same seed draws the same staircases

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// How a nominal plan fared on perturbed stairs, open loop and replanned.
struct RobustnessReport {
  int trials = 0;  ///< perturbed staircases evaluated
  int nominal_valid = 0;  ///< 1 when the plan is valid on the nominal stairs
  int open_loop_ok = 0;   ///< trials where the nominal plan is still valid on the true stairs
  int replanned_ok = 0;   ///< trials where a plan made on the true stairs is valid
  double worst_cumulative_run_error = 0.0;  ///< largest |sum of run errors| over the trials [m]
};

/// The perturbed staircases EvaluateRobustness draws for `settings` (same seed, same order), so that
/// other judges (the physics check) run on the same stairs.
std::vector<StairSpec> PerturbedStaircases(const StairSpec& nominal, const RobustnessSettings& settings);

/// The nominal plan moved onto `true_stairs`: footholds keep x and y and take the true height.
Plan PlanOnTrueStairs(const Plan& nominal, const Staircase& true_stairs, const ConstrainedMap& true_map);

/// Plans `nominal`, then for each of PerturbedStaircases(): the nominal plan executed open loop on
/// the perturbed stairs, and a new plan made on them, both validated there (not per cycle).
RobustnessReport EvaluateRobustness(const RobotModel& robot, const StairSpec& nominal, const PipelineOptions& options,
                                    const RobustnessSettings& settings);

}  // namespace stairplan
