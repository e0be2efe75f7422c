// The built-in robot, stairbot (data/robots/stairbot.urdf), compiled into the library so that a
// plan needs no file on disk.
#pragma once

#include <string>

#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

/// The URDF text of stairbot.
const std::string& BuiltinRobotUrdf();
/// stairbot loaded as a RobotModel (source "builtin:stairbot").
const RobotModel& BuiltinRobot();

}  // namespace stairplan
