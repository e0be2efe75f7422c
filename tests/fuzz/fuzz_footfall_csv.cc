// libFuzzer target: the footfall CSV reader. Accepted footfalls are finite.
#include <cmath>
#include <cstdio>

#include "fuzz_check.h"
#include "stairplan/perception/footfall.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto footfalls = stairplan::ParseFootfallCsv(stairplan::fuzz::Text(data, size), "fuzz.csv");
    for (const auto& f : footfalls) {
      if (!std::isfinite(f.t) || !f.position.allFinite()) {
        std::fprintf(stderr, "finding: the footfall reader accepted a non-finite footfall\n");
        std::abort();
      }
    }
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.csv");
  }
  return 0;
}
