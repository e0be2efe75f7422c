// libFuzzer target: the URDF loader (XML check, canonical text, urdfdom parse, capsule check, leg
// detection, limits). The canonical text urdfdom gets must be printable ASCII and a fixed point:
// checked again, it comes back unchanged.
#include <cstdio>
#include <cstdlib>

#include "fuzz_check.h"
#include "stairplan/kinematics/checked_xml.h"
#include "stairplan/kinematics/robot_model.h"

namespace {

void CheckCanonical(const std::string& text) {
  std::string canonical;
  try {
    canonical = stairplan::CheckedXml(text, "fuzz.urdf").Canonical();
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.urdf");
    return;
  }
  for (const char ch : canonical) {
    if (ch != '\n' && (ch < 0x20 || ch > 0x7E)) {
      std::fprintf(stderr, "finding: the canonical text has byte 0x%02X\n", static_cast<unsigned char>(ch));
      std::abort();
    }
  }
  if (stairplan::CheckedXml(canonical, "canonical.urdf").Canonical() != canonical) {
    std::fprintf(stderr, "finding: the canonical text changes when checked again:\n%s\n", canonical.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = stairplan::fuzz::Text(data, size);
  CheckCanonical(text);
  try {
    const auto robot = stairplan::RobotModel::FromUrdfString(text, "fuzz.urdf");
    (void)robot.hip_length();
    (void)robot.hip_width();
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.urdf");
  }
  return 0;
}
