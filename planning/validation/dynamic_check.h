// The validator's dynamic check at one instant: the wrench the plan's motion asks for
// (centroidal_demand.h) against what the stance feet can give (contact_wrench_qp.h), with each
// stance leg's torque map -J^T R^T from its joint angles and its joints' effort limits from the URDF.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "kinematics/body_pose.h"
#include "kinematics/robot_kinematics.h"
#include "planning/plan.h"
#include "planning/validation/centroidal_demand.h"
#include "planning/validation/contact_wrench_qp.h"

namespace stairplan {

/// The dynamic check of one instant: the demand of the plan's motion against the stance feet.
class DynamicCheck {
 public:
  /// `acceleration_window`: the h of CentroidalModel [s].
  DynamicCheck(const RobotKinematics& kinematics, const ContactWrenchSettings& settings, double acceleration_window);

  /// The contact forces' best try at the demand of `body_samples` at time t, for the legs (in
  /// kinematics order) at joint angles `q` with contact points `feet_W`, `stance` telling which
  /// are down, and the centre of mass at `com_W`.
  const ContactWrenchResult& Check(const std::vector<BodyState>& body_samples, double t, const BodyPose& body,
                                   const std::array<Eigen::Vector3d, 4>& q, const std::array<Eigen::Vector3d, 4>& feet_W,
                                   const std::array<bool, 4>& stance, const Eigen::Vector3d& com_W, RobotWorkspace& ws);

  /// The robot's weight [N]: the scale of the residual.
  double weight() const;

 private:
  const RobotKinematics& kinematics_;
  CentroidalModel model_;
  ContactWrenchQp qp_;
  std::array<Eigen::Vector3d, 4> effort_{};
  std::array<ContactFoot, 4> feet_{};
};

}  // namespace stairplan
