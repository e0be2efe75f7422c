// Legs by their place on the body, for verdicts that name one: the RobotModel's order (LF, RF,
// LH, RH), so a leg index of the kinematics converts directly.
#pragma once

namespace stairplan {

/// A leg by its place on the body; kNone: no single leg (the body, a pair, or no leg at all).
enum class LegId { kLeftFront, kRightFront, kLeftHind, kRightHind, kNone };

/// "LF", "RF", "LH", "RH" (the RobotModel's leg names), "none".
const char* ToString(LegId leg);

/// The leg at `index` of the RobotModel's order; kNone outside 0..3.
LegId LegIdFromIndex(int index);

}  // namespace stairplan
