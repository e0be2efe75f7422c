// Position-only inverse kinematics of a 3-DoF leg: the outcome types and settings.
#pragma once

#include <Eigen/Core>

namespace stairplan {

/// How an IK solve ended. Outcomes, not errors: nothing here throws.
enum class IkStatus {
  kSolved,       ///< the foot reaches the target within tolerance, joints within limits
  kOutOfReach,   ///< no joint configuration reaches the target, even ignoring the limits
  kJointLimits,  ///< the target is reachable only with a joint outside its limits
};
/// Returns "solved", "out_of_reach" or "joint_limits".
const char* ToString(IkStatus status);

/// Settings of the damped Gauss-Newton solver with box-projected steps and restarts.
struct IkSettings {
  double tolerance = 1e-9;      ///< foot position error accepted as solved [m]
  int max_iterations = 40;      ///< per attempt
  int max_restarts = 8;         ///< further seeds tried when the first attempt stalls at a limit
  double max_step = 0.5;        ///< largest joint step per iteration [rad]

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The result of one solve: the best joint angles found (within limits), the remaining error.
struct IkResult {
  IkStatus status = IkStatus::kOutOfReach;  ///< how the solve ended
  Eigen::Vector3d q = Eigen::Vector3d::Zero();  ///< joint angles [rad], always within limits
  double error = 0.0;                           ///< |FK(q) - target| [m]
  int iterations = 0;                           ///< Gauss-Newton iterations over all attempts
  /// True when the foot reached the target within the limits.
  bool ok() const { return status == IkStatus::kSolved; }
};

}  // namespace stairplan
