// libFuzzer target: the stairs YAML reader. A spec it accepts must also build a Staircase (the
// reader promises a validated spec).
#include <cstdio>

#include "fuzz_check.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "stairplan/geometry/staircase.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stairplan::StairSpec spec;
  try {
    spec = stairplan::StairSpecFromYaml(stairplan::fuzz::Text(data, size), "fuzz.yaml");
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.yaml");
    return 0;
  }
  try {
    const stairplan::Staircase stairs(spec);
    (void)stairs;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "finding: the YAML reader accepted a spec that Staircase rejects: %s\n", e.what());
    std::abort();
  }
  return 0;
}
