// The `stairplan plan` flags of the body optimisation as it is about to become the default
// planner: the perception CLI tests plan with them as well as with the quasi-static default.
#pragma once

namespace stairplan::testing {

inline constexpr const char* kBodyOptimisation =
    "--body qp --set body.stance_rows=1 --set body.stability_margin=0.03 --set body.hip_height_fraction=0.6 "
    "--set body.max_shift=0.15 --set body.max_lateral_shift=0.15 --set body.acceleration_weight=1";

}  // namespace stairplan::testing
