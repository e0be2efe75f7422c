// plan.svg: a side view of a plan that anyone can read: the stairs, step regions in green,
// collision regions in red, the footholds of each leg, the body path, axes in metres.
#pragma once

#include <string>

#include "geometry/constrained_map.h"
#include "geometry/staircase.h"
#include "planning/plan.h"

namespace stairplan {

std::string PlanToSvg(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map);

}  // namespace stairplan
