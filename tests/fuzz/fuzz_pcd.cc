// libFuzzer target: the PCD point-cloud reader (ascii, binary and binary_compressed with our LZF
// decoder).
#include "cloud_check.h"
#include "fuzz_check.h"
#include "stairplan/perception/pcd_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    stairplan::fuzz::CheckCloud(stairplan::ParsePcd(stairplan::fuzz::Text(data, size), "fuzz.pcd"), "PCD");
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.pcd");
  }
  return 0;
}
