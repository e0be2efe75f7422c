// The body QP's model of the centre of mass, affine in the body's horizontal position:
//   COM_xy = gain .* body_xy + foot_gain .* sum_legs foot_xy + offset + pitch_slope (pitch - pitch0)
// Feet in stance stay where they are, so the legs follow the body only in part (gain < 1); the
// whole robot moved rigidly moves its COM alike (gain + 4 foot_gain = 1). Calibrated once, by
// finite differences of ComModel (every leg through IK) around the start stance, for the plan's
// yaw. The validator's COM (swing legs on their own paths, joint angles far from the start)
// differs by millimetres, which BodyPlannerSettings::stability_margin covers.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// The body QP's affine model of the centre of mass (see the file's top comment).
struct ComEstimate {
  Eigen::Vector2d gain = Eigen::Vector2d::Ones();       ///< d COM / d body, per world axis
  Eigen::Vector2d foot_gain = Eigen::Vector2d::Zero();  ///< d COM / d foot, per foot and axis
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();     ///< [m]
  Eigen::Vector2d pitch_slope = Eigen::Vector2d::Zero();  ///< d COM / d pitch [m/rad]
  double pitch0 = 0.0;                                  ///< pitch of the calibration [rad]

  /// The estimate for the body at (body_xy, pitch) over feet whose horizontal positions sum to `feet_sum`.
  Eigen::Vector2d At(const Eigen::Vector2d& body_xy, const Eigen::Vector2d& feet_sum, double pitch) const {
    return gain.cwiseProduct(body_xy) + foot_gain.cwiseProduct(feet_sum) + offset + pitch_slope * (pitch - pitch0);
  }
};

/// Calibrates the estimate for the robot of `kinematics` standing on `contacts_W` (contact points,
/// robot leg order) with the body at `body`. Not per cycle (IK of every leg a few times).
ComEstimate CalibrateComEstimate(const RobotKinematics& kinematics, const std::array<Eigen::Vector3d, 4>& contacts_W,
                                 const BodyState& body);

}  // namespace stairplan
