// libFuzzer target: the plan.json reader behind `stairplan validate`. An accepted plan has finite
// numbers and a valid stairs model.
#include <cstdio>

#include "fuzz_check.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan_json_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const stairplan::PlanFile file = stairplan::ReadPlanJson(stairplan::fuzz::Text(data, size), "fuzz.json");
    const stairplan::Staircase stairs(file.stairs);  // the reader validated the spec: must not throw
    (void)stairs;
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.json");
  }
  return 0;
}
