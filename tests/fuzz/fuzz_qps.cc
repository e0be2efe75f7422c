// libFuzzer target: the QPS reader (Maros-Meszaros format) into a Program.
#include "fuzz_check.h"
#include "stairplan/optim/qps_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto qp = stairplan::optim::ParseQps(stairplan::fuzz::Text(data, size), "fuzz.qps");
    (void)qp.program.num_variables();
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.qps");
  }
  return 0;
}
