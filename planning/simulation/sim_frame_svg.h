// A side view (x-z) of one simulated state as SVG: the stairs' profile, the robot as a stick figure
// joining each body to its parent, the foot spheres, and the plan's targets. MuJoCo's own renderer
// needs an OpenGL context, which a headless build machine lacks; this needs nothing.
#pragma once

#include <string>

#include "geometry/staircase.h"
#include "planning/plan.h"
#include "planning/simulation/sim_outcome.h"

namespace stairplan {

/// The SVG text of `frame` on `stairs`; footholds of `plan` are marked.
std::string SimFrameSvg(const SimFrame& frame, const Staircase& stairs, const Plan& plan);

}  // namespace stairplan
