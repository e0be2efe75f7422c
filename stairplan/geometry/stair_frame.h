// A staircase's own frame placed in the world: the frame a plan on stairs found by perception or
// footfalls is made in (StairModel::ToStaircase), and the world its robot is tracked in. Converts
// the robot's tracked poses into the plan's frame and the plan's poses back.
#pragma once

#include "stairplan/geometry/ground_pose.h"
#include "stairplan/geometry/stair_model.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// The frame of model.ToStaircase(travel, nosing) in the world.
struct StairFrame {
  StairModel model;  ///< the staircase in the world
  TravelDirection travel = TravelDirection::kUp;  ///< how it is traversed
  double nosing = 0.0;  ///< the nosing the Staircase was made with [m]

  /// A pose of the staircase's frame in the world.
  GroundPose ToWorld(const GroundPose& pose_S) const;
  /// A pose of the world in the staircase's frame.
  GroundPose ToStair(const GroundPose& pose_W) const;
};

}  // namespace stairplan
