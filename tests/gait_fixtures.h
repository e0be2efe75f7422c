// What the gaits' tests (the walk's and the trot's, planned and executed) share: the default
// stairs one way, and a plan of the built-in robot judged again on stairs of another friction.
#pragma once

#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan::testing {

/// The default stairs travelled `direction`, with `steps` risers.
inline Staircase DefaultStairs(TravelDirection direction, int steps = StairSpec{}.steps) {
  StairSpec spec;
  spec.direction = direction;
  spec.steps = steps;
  return Staircase(spec);
}

/// The built-in robot's `plan` on `stairs` validated with the stairs' friction coefficient set to
/// `friction`, on the map the pipeline builds.
inline ValidationReport ValidateOnFriction(const Plan& plan, const Staircase& stairs, double friction) {
  const RobotModel robot = BuiltinRobot();
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, PipelineOptions{});
  ValidationSettings settings;
  settings.dynamics.friction = friction;
  TraversalValidator validator(robot, stairs, map, settings);
  return validator.Validate(plan);
}

}  // namespace stairplan::testing
