// Settings of the step planner and of its offline driver: the controllers (cadences x gaits), the
// horizon, the cost weights and the hard limits. Defaults suit a medium quadruped on
// building-code stairs.
#pragma once

#include <vector>

#include "stairplan/planning/step/gait_pattern.h"

namespace stairplan {

/// The step planner's controllers, rule-outs, targets and cost weights.
struct StepPlannerSettings {
  // --- Controllers (US 2020/0324412 [0033]): every cadence with every gait.
  /// Swing durations of the fixed-cadence controllers [s]; 0.25 to 0.45 s in 0.05 s steps.
  std::vector<double> cadences_s = {0.25, 0.30, 0.35, 0.40, 0.45};
  /// Gaits; each is combined with every cadence.
  std::vector<Gait> gaits = {Gait::kCrawl, Gait::kCrawlAlternate, Gait::kTrot};
  /// Footsteps in each controller's step plan (the horizon).
  int horizon_steps = 8;

  // --- The body the step plans assume (until the body planner provides it).
  /// Hip height above the stairs' pitch line, as a fraction of the mean leg reach.
  double hip_height_fraction = 0.65;

  // --- Hard rule-outs (US 2020/0324412 [0035]: conditions checked before scoring).
  /// The highest step a leg can clear, as a fraction of its max_reach.
  double max_step_height_fraction = 0.45;
  /// Geometric reach band (hip to foot centre) as fractions of max_reach, used when no other
  ///@{
  /// ReachModel is given.
  double reach_min_fraction = 0.30;
  double reach_max_fraction = 0.95;
  ///@}

  // --- Targets.
  /// Targets are put at least this far inside their step region (less on very narrow regions) [m].
  double target_margin = 0.01;
  /// Stairs on either side of the nearest step region that are tried when it breaks a rule.
  int candidate_stairs = 2;

  // --- Cost weights (US 2020/0324412 [0035]: the distance to the step regions dominates).
  double region_weight = 1000.0;   ///< per m of distance from the nearest step region
  double snap_weight = 100.0;      ///< per m the chosen target lies beyond that distance (rules)
  double trailing_cost = 20.0;     ///< per footstep that puts a trailing leg ahead of its leading leg
  double swing_height_weight = 1.0;  ///< times (needed step height / the robot's)^2
  double reach_weight = 1.0;       ///< times the reach model's effort^2, at touchdown
  double timing_weight = 1.0;      ///< times (swing speed above max_foot_speed [m/s])^2 per (m/s)^2
  double max_foot_speed = 1.5;     ///< comfortable foot speed in swing [m/s]
  double switch_cost = 0.5;        ///< added to every controller but the current one (hysteresis)
  double gait_switch_cost = 5.0;   ///< added on top when the controller's gait differs from the current one

  // --- Offline driver (PlanWithStepPlanner).
  double speed = 0.15;           ///< commanded body speed along the stairs [m/s]
  double sample_period = 0.05;   ///< body trajectory sampling [s]
  double start_gap = 0.10;       ///< fore feet this far before the end of the first step region [m]
  /// Four feet down at the start before the first swing, the body already moving [s]. The driver's
  /// body keeps a constant speed and does not shift the COM between support triangles; that is the
  /// body planner's job.
  double settle_s = 0.0;
  int max_cycles = 20000;        ///< bound on re-selections in one traversal

  /// Throws std::invalid_argument naming the field (e.g. "cadences_s[2]", "horizon_steps").
  void Validate() const;
};

}  // namespace stairplan
