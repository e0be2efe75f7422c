#include "stairplan/kinematics/leg_ik.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace stairplan {

const char* ToString(IkStatus status) {
  switch (status) {
    case IkStatus::kSolved: return "solved";
    case IkStatus::kOutOfReach: return "out_of_reach";
    case IkStatus::kJointLimits: return "joint_limits";
  }
  return "unknown";
}

void IkSettings::Validate() const {
  if (!std::isfinite(tolerance) || tolerance <= 0.0) {
    throw std::invalid_argument("IkSettings.tolerance: must be positive (got " + std::to_string(tolerance) + ")");
  }
  if (max_iterations < 1) throw std::invalid_argument("IkSettings.max_iterations: must be at least 1");
  if (max_restarts < 0) throw std::invalid_argument("IkSettings.max_restarts: must not be negative");
  if (!std::isfinite(max_step) || max_step <= 0.0) {
    throw std::invalid_argument("IkSettings.max_step: must be positive (got " + std::to_string(max_step) + ")");
  }
}

}  // namespace stairplan
