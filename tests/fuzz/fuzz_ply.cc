// libFuzzer target: the PLY point-cloud reader (ascii and binary little-endian).
#include "cloud_check.h"
#include "fuzz_check.h"
#include "stairplan/perception/ply_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    stairplan::fuzz::CheckCloud(stairplan::ParsePly(stairplan::fuzz::Text(data, size), "fuzz.ply"), "PLY");
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.ply");
  }
  return 0;
}
