// The rows that keep one stance leg within reach and its joint limits, linearised around a body
// pose with the leg's Jacobian: the foot stays on its contact point while the body moves, so the
// foot's position in the base frame moves by D dv (D: its derivative in the body variables) and
// the joints by J^-1 D dv. The body QP puts one such set per stance leg and knot into its rows.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/leg_kinematics.h"

namespace stairplan {

/// The body variables the rows are written in, as increments from the linearisation pose:
/// height, pitch, and the displacement along the heading and sideways of it (yaw is fixed).
enum BodyVariable { kBodyZ = 0, kBodyPitch = 1, kBodyAlong = 2, kBodySideways = 3 };

/// lo <= a . dv <= hi for every row; rows 0-2 are the joints (hip abduction, flexion, knee), row 3
/// the leg's extension (flexion joint to foot), row 4 the foot's distance from the first joint's
/// axis. Each row's coefficients have unit length, so its bounds read as the
/// distance dv may move in metres (or radians of pitch) before it binds.
struct StanceLegRows {
  static constexpr int kRows = 5;  ///< rows per stance leg: three joints, the extension, the axis distance
  std::array<Eigen::Vector4d, kRows> a{};  ///< each row's unit coefficients over (z, pitch, along, sideways)
  ///@{
  std::array<double, kRows> lo{}, hi{};  ///< each row's bounds
  ///@}
  Eigen::Vector3d q = Eigen::Vector3d::Zero();  ///< the joints at the pose (IK; within limits)
  /// The joints' change per unit change of (z, pitch, along, sideways), the foot held; zero near a
  /// singularity.
  Eigen::Matrix<double, 3, 4> dq = Eigen::Matrix<double, 3, 4>::Zero();
  bool reached = false;  ///< IK put the foot on its contact within the limits at the pose
};

/// Margins the rows keep inside the limits.
struct StanceLegMargins {
  double joint = 0.0;  ///< [rad]
  double reach = 0.0;  ///< extension (flexion joint to foot distance) [m]
  /// How far beyond the leg plane's offset the foot keeps from the first joint's axis, where more
  /// than `reach` [m].
  double axis = 0.0;
  /// How far a moving foot's path strays from its chords to the knots before and after, at their
  /// middles (world frame; zero for a foot that stays put) [m]. Between knots the body moves
  /// linearly while a swing foot follows its curve (it slows to touch down), so the joints and
  /// the extension there differ from the knots' average by what this departure causes; the rows
  /// keep that much more inside the limits, on the side the departure moves them towards.
  std::array<Eigen::Vector3d, 2> foot_bends_W{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

/// Rows of leg `kin` whose foot origin stays at `foot_W` with the body at `pose` (its yaw a
/// multiple of pi: the heading frame is the world's, turned). `seed` starts the IK. Allocation-free.
StanceLegRows LinearizeStanceLeg(const LegKinematics& kin, LegWorkspace& ws, const Eigen::Vector3d& foot_W,
                                 const BodyPose& pose, const Eigen::Vector3d& seed, const StanceLegMargins& margins);

}  // namespace stairplan
