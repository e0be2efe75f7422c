// libFuzzer target: the whitespace XYZ point-cloud reader.
#include "cloud_check.h"
#include "fuzz_check.h"
#include "stairplan/perception/xyz_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    stairplan::fuzz::CheckCloud(stairplan::ParseXyz(stairplan::fuzz::Text(data, size), "fuzz.xyz"), "XYZ");
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.xyz");
  }
  return 0;
}
