// The step planner's offline driver: walks the body along the stairs at the commanded speed,
// re-selecting a controller every cycle (every swing phase), and records the result as a Plan.
#pragma once

#include <memory>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/step/reach_model.h"
#include "stairplan/planning/step/step_planner_settings.h"

namespace stairplan {

/// Plans a traversal of `stairs` for `robot` on `map` with the step planner: footsteps for the
/// whole traversal (all inside step regions), body samples (x, z, pitch) every sample_period,
/// cadence_s and gait of the controller chosen most often, and per-controller scores. Never throws
/// for geometry it cannot handle: status kInfeasible with a reason naming each controller's rule,
/// or, before any cycle, the rise no leg can step (FirstRiseTooHigh).
/// Throws std::invalid_argument for bad settings.
Plan PlanWithStepPlanner(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                         const StepPlannerSettings& settings = {}, std::shared_ptr<const ReachModel> reach = nullptr);

}  // namespace stairplan
