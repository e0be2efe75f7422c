// The step planner's step-height rule (US 2020/0324412 [0035]: a footstep higher than the leg can
// clear rules its controller out) applied to a whole flight. Every foot crosses each rise of the
// flight in one swing at least (skipping a tread only makes that swing's step higher), so a rise
// higher than some leg can step rules out every controller whatever its cadence or gait: the
// flight is infeasible for the robot, and the rise is the binding constraint.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/step/step_planner_settings.h"

namespace stairplan {

/// The highest step `leg` can take: StepPlannerSettings::max_step_height_fraction of its reach [m].
double MaxStepHeight(const LegModel& leg, const StepPlannerSettings& settings);

/// A rise of the flight higher than a leg can step.
struct RiseTooHigh {
  int surface = 0;           ///< the map surface the rise leads onto, in travel order
  double rise = 0.0;         ///< its height difference to the surface before it [m]
  std::string leg;           ///< the leg with the lowest step height
  double max_step = 0.0;     ///< that leg's MaxStepHeight [m]
  double max_reach = 0.0;    ///< that leg's reach (LegModel::max_reach) [m]
  double fraction = 0.0;     ///< StepPlannerSettings::max_step_height_fraction
};

/// The first rise of `map` (between consecutive surfaces, up or down) higher than the lowest step
/// of `legs`, or nullopt when every leg can step every rise.
std::optional<RiseTooHigh> FirstRiseTooHigh(const std::vector<LegModel>& legs, const ConstrainedMap& map,
                                            const StepPlannerSettings& settings);

/// The rule in words, e.g. "step height: the rise onto surface 1 is 0.170 m, higher than RF can
/// step (0.152 m: max_step_height_fraction 0.45 of its 0.338 m reach)".
std::string ToString(const RiseTooHigh& rise);

}  // namespace stairplan
