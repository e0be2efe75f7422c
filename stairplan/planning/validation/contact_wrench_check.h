// The validator's dynamic-feasibility check for one robot: at an instant of a plan, the wrench
// the body's motion needs (m (a - g) from the COM acceleration, dL/dt from the body's angular
// acceleration and the URDF inertia of the base and the links fixed to it) must come from the
// stance feet's contact forces inside their friction pyramids and within the legs' effort limits
// (tau = J^T f with the KDL foot Jacobian). The QP is ContactWrenchQp; this file turns the robot and the instant into its input.
//
// What it leaves out, knowingly: the legs' own inertia and weight in the joint torques (the legs
// are light beside the base), the momentum of the legs' motion, the Euler-rate products of the
// angular acceleration, and the foot radius between the foot link's origin (the Jacobian's point)
// and the contact point.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/validation/body_rates.h"
#include "stairplan/planning/validation/contact_wrench_qp.h"

namespace stairplan {

/// The robot's state at one instant as the validator replays it.
struct WrenchInstant {
  BodyPose body;                                 ///< base pose
  BodyRates rates;                               ///< base accelerations
  Eigen::Vector3d com_W = Eigen::Vector3d::Zero();  ///< centre of mass [m]
  std::array<Eigen::Vector3d, 4> feet_W{};       ///< contact points, LF, RF, LH, RH [m]
  std::array<Eigen::Vector3d, 4> normals_W{};    ///< unit normals of the surfaces under the feet
  std::array<bool, 4> stance{};                  ///< which feet carry load
  std::array<Eigen::Vector3d, 4> q{};            ///< the legs' joint angles [rad]
};

/// Two feet standing at an instant: the moment about the line between them that the instant's
/// wrench asks of them and no force there can give (ContactWrenchSettings::max_line_tilt), and
/// how the body would tip about that line.
struct LineSupport {
  bool active = false;  ///< exactly two feet stand
  int pair = 0;         ///< which two: a bit per leg, LF 1, RF 2, LH 4, RH 8
  double moment = 0.0;  ///< the moment about the line the feet cannot give [N m]
  double inertia = 0.0;  ///< the robot's inertia about the line [kg m^2]
  /// The gravito-inertial moment about the line per radian of tilt (positive: it topples) [N m/rad].
  double stiffness = 0.0;
};

/// Built once per robot; Check() per instant. Not thread-safe (owns the QP and its workspace).
class ContactWrenchCheck {
 public:
  /// `mass` is the robot's total mass [kg] (the COM model's). Throws std::invalid_argument naming
  /// the field for bad settings.
  ContactWrenchCheck(const RobotKinematics& kinematics, double mass, const ContactWrenchSettings& settings = {});

  /// The QP's answer at `instant` (the leg Jacobians use `ws`).
  const WrenchResult& Check(const WrenchInstant& instant, RobotWorkspace& ws);

  /// False when some joint of the URDF has no effort limit (effort <= 0): then no torque row binds.
  bool torque_limits_checked() const { return torque_limits_checked_; }
  /// False when neither the base link nor a link fixed to it has a URDF inertia: then dL/dt is zero.
  bool body_inertia_known() const { return body_inertia_known_; }
  /// The residual above which an instant fails [N].
  double tolerance() const { return qp_.tolerance(); }
  /// The last Check()'s two-foot support (inactive with more or fewer feet); its moment about the
  /// line is not part of the QP's wrench.
  const LineSupport& line() const { return line_; }

 private:
  const RobotKinematics& kinematics_;
  double mass_ = 0.0;
  Eigen::Matrix3d inertia_B_ = Eigen::Matrix3d::Zero();  // base and fixed links, about their centre, base axes
  bool body_inertia_known_ = false;
  bool torque_limits_checked_ = false;
  std::array<Eigen::Vector3d, 4> effort_{};
  ContactWrenchQp qp_;
  std::array<WrenchFoot, 4> feet_{};
  LineSupport line_;
  // Takes the moment about the line of two standing feet out of `demand` into line_.
  void SplitLineMoment(const WrenchInstant& instant, const Eigen::Matrix3d& inertia_W, WrenchDemand& demand);
};

}  // namespace stairplan
