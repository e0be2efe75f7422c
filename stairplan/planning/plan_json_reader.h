// Reading plan.json back (for `stairplan validate` and `simulate`): the plan, the stairs it was
// made for, the facing and the robot's source. Errors name the file and the JSON field.
#pragma once

#include <string>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// What a plan.json holds: the plan, the stairs it was planned on and the body's facing.
struct PlanFile {
  Plan plan;  ///< the plan
  StairSpec stairs;  ///< the stairs, as written in the file
  Facing facing = Facing::kForward;  ///< which way the body faced
};

/// Parses plan.json text. Throws std::invalid_argument "<source>: field '<path>': <problem>", also
/// for a schema_version newer than kSchemaVersion.
PlanFile ReadPlanJson(const std::string& text, const std::string& source);
/// Reads and parses a plan.json file.
PlanFile ReadPlanJsonFile(const std::string& path);

}  // namespace stairplan
