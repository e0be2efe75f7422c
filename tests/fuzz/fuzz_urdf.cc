// libFuzzer target: the URDF loader (urdfdom parse, capsule check, leg detection, limits).
#include "fuzz_check.h"
#include "kinematics/robot_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto robot = stairplan::RobotModel::FromUrdfString(stairplan::fuzz::Text(data, size), "fuzz.urdf");
    (void)robot.hip_length();
    (void)robot.hip_width();
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, "fuzz.urdf");
  }
  return 0;
}
