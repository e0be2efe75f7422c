// The margins a plan keeps to be valid, owned here once: the validator judges by them (its
// settings' defaults) and the body planner's exact re-check asks them of the plans it returns.
#pragma once

namespace stairplan {

/// How far inside the standing feet's polygon a quasi-static gait keeps its centre of mass [m].
inline constexpr double kValidStabilityMargin = 0.01;

}  // namespace stairplan
