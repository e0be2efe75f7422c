// The body planner's offline driver: runs the receding-horizon planner along a footstep plan (as
// the control loop would, one cycle per knot) and writes the executed body trajectory, with its
// com_shift, into the plan; then re-checks it exactly (IK and FCL). `stairplan plan` calls it.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/body/body_check.h"
#include "stairplan/planning/body/body_planner_settings.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// What the exact re-check asks of a body planned with `settings` for a plan of `gait`: the
/// clearance margin; the checked stability margin where the QP has stability rows and the gait
/// balances quasi-statically; the retreat bound where it has stance rows (they price retreat).
BodyCheckMargins RecheckMargins(const BodyPlannerSettings& settings, const std::optional<Gait>& gait);

/// Fills `footsteps_plan.body` (one sample per knot_dt) from the body planner and returns the
/// plan. Its status becomes infeasible, with the reason, when a cycle finds no valid body height
/// for a stance leg, a QP fails, or the exact re-check (body_check.h, with RecheckMargins()) finds
/// a leg out of reach, a leg, a pair of legs or the body closer than settings.clearance_margin,
/// the centre of mass nearer the support's edge than settings.checked_stability_margin, or the
/// body moving back along the travel by more than settings.max_retreat. A plan that is already
/// infeasible is returned as it is. Throws std::invalid_argument naming the field for bad settings. `standing_xy`, where
/// known, is where the robot's body stands at the start (the alignment pose it walked to): the
/// plan starts there, its offset from the neutral body as the start's weight shifts; otherwise it
/// starts over the feet (BodyPlanner::StartState()). With `stop_at_first_violation`, each sample
/// is re-checked as it is planned and the plan ends, infeasible, at the first that fails: for a
/// caller that needs the verdict only (a search over footholds), not the count of violations.
Plan PlanBody(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, Plan footsteps_plan,
              const BodyPlannerSettings& settings = {}, const std::optional<Eigen::Vector2d>& standing_xy = std::nullopt,
              bool stop_at_first_violation = false);
/// The same on the robot's kinematics built already (a caller planning many bodies builds them once).
Plan PlanBody(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map, Plan footsteps_plan,
              const BodyPlannerSettings& settings = {}, const std::optional<Eigen::Vector2d>& standing_xy = std::nullopt,
              bool stop_at_first_violation = false);

}  // namespace stairplan
