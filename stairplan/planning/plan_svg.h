// plan.svg: a plan that anyone can read: a side view (stairs, step and collision regions, the
// footholds on their treads, the body path) over a top view (the regions and footholds in x-y, the
// body's sideways shift), axes in metres, violations marked where and when they happened, and a
// title that says INVALID with the first violation when the plan failed validation.
#pragma once

#include <string>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan {

/// The SVG text; `validation` (null: not validated) decides the title and the marks.
std::string PlanToSvg(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map,
                      const ValidationReport* validation = nullptr);

}  // namespace stairplan
