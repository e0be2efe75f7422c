// The `stairplan plan` flags of the quasi-static path baseline (the planner before the body
// optimisation became the default): the perception CLI tests plan with them as well as with the
// default, so that the baseline keeps planning what it planned.
#pragma once

namespace stairplan::testing {

inline constexpr const char* kPathBaseline = "--body path --crawl-sequence pairs";

}  // namespace stairplan::testing
