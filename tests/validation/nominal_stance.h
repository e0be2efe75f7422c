// A robot standing on its legs' nominal configurations on flat ground, as the dynamic check's
// input: for tests of ContactWrenchCheck that need real leg Jacobians.
#pragma once

#include "stairplan/planning/validation/contact_wrench_check.h"

namespace stairplan::testing {

/// Body 0.45 m up, every foot in stance at its nominal configuration, normals up, COM 0.1 m above
/// the feet's centre, no acceleration.
inline WrenchInstant NominalStance(const RobotKinematics& kinematics, RobotWorkspace& ws) {
  WrenchInstant instant;
  instant.body.position_W = {0.0, 0.0, 0.45};
  instant.com_W.setZero();
  for (int l = 0; l < 4; ++l) {
    const auto i = static_cast<std::size_t>(l);
    instant.q[i] = kinematics.leg(l).nominal();
    instant.feet_W[i] = instant.body.ToIsometry() * kinematics.leg(l).FootPosition(instant.q[i], ws.leg(l));
    instant.normals_W[i] = Eigen::Vector3d::UnitZ();
    instant.stance[i] = true;
    instant.com_W += 0.25 * instant.feet_W[i] + Eigen::Vector3d(0, 0, 0.025);
  }
  return instant;
}

}  // namespace stairplan::testing
