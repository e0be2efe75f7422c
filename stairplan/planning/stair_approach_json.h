// plan.json's "stair_mode" and "alignment" objects (PCT/US2021/022953 ("Identifying stairs from
// footfalls") [0042]-[0043]): whether stair mode is engaged at the robot's pose and where that pose
// came from; the alignment pose the plan starts from, its stance, the robot's move to it and how
// far the plan's first body state is from it. In the plan's frame, and in the world when the
// stairs were found there (a cloud, footfalls).
#pragma once

#include <nlohmann/json.hpp>

#include "stairplan/geometry/stair_frame.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/stair_approach.h"

namespace stairplan {

/// {"stair_mode": {...}, "alignment": {...}} for `approach` and the plan made from it; `world`
/// (may be null: the plan's frame is the world) adds each pose in the world.
nlohmann::json StairApproachToJson(const StairApproach& approach, const Plan& plan, const StairFrame* world);

}  // namespace stairplan
