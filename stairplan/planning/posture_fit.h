// The posture fit of the quasi-static body path (stairplan/planning/body_path.h): moves the body, by a
// height change and a shift along the flight, into postures whose stance passes the stance check
// (IK within limits, legs clear of the stairs) with the swing feet on their swings.
//
// Each swing gets one shift, and one height or a height eased from liftoff to touchdown, that every
// instant of it accepts, so the body barely moves while the support is a triangle; corrections
// change while all four feet are down, eased over that whole phase, whose instants are checked too
// (and repaired with a key where one fails). A correction that jumps between nearby instants is
// what makes a plan that is statically fine fall over when executed (the executor must accelerate
// the body many m/s^2 to follow it).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

struct BodyPathSettings;

/// Fits the corrections and applies them to `body` (samples sorted by time). `com_target` is
/// where the path wants the centre of mass at time t (the shift keeps it inside the support).
void FitPosturesToStances(const RobotModel& robot, const Staircase& stairs, const std::vector<std::string>& legs,
                          const std::vector<Eigen::Vector3d>& initial, const std::vector<Footstep>& footsteps,
                          const std::function<Eigen::Vector2d(double)>& com_target, const BodyPathSettings& settings,
                          std::vector<BodyState>& body);

}  // namespace stairplan
