#include "planning/validation/dynamic_check.h"

#include <Eigen/Geometry>

namespace stairplan {

DynamicCheck::DynamicCheck(const RobotKinematics& kinematics, const ContactWrenchSettings& settings,
                           double acceleration_window)
    : kinematics_(kinematics), model_(kinematics.robot(), acceleration_window), qp_(settings) {
  for (int l = 0; l < kinematics.leg_count() && l < 4; ++l) {
    const std::vector<JointLimits>& limits = kinematics.leg(l).model().limits;
    Eigen::Vector3d& effort = effort_[static_cast<std::size_t>(l)];
    for (int j = 0; j < 3; ++j) {
      // A URDF without an effort limit (0) states none.
      const double e = j < static_cast<int>(limits.size()) ? limits[static_cast<std::size_t>(j)].effort : 0.0;
      effort[j] = e > 0.0 ? e : optim::kInf;
    }
  }
}

double DynamicCheck::weight() const { return model_.mass() * 9.81; }

const ContactWrenchResult& DynamicCheck::Check(const std::vector<BodyState>& body_samples, double t, const BodyPose& body,
                                               const std::array<Eigen::Vector3d, 4>& q,
                                               const std::array<Eigen::Vector3d, 4>& feet_W,
                                               const std::array<bool, 4>& stance, const Eigen::Vector3d& com_W,
                                               RobotWorkspace& ws) {
  const Eigen::Matrix3d rotation = body.ToIsometry().linear();
  for (int l = 0; l < kinematics_.leg_count() && l < 4; ++l) {
    const auto i = static_cast<std::size_t>(l);
    ContactFoot& foot = feet_[i];
    foot.stance = stance[i];
    foot.position_W = feet_W[i];
    foot.effort = effort_[i];
    // The ground pushes the foot with f; the joints hold it with -J^T f (f in the base frame).
    if (foot.stance) foot.torque_map = -kinematics_.leg(l).FootJacobian(q[i], ws.leg(l)).transpose() * rotation.transpose();
  }
  const CentroidalDemand demand = model_.DemandAt(body_samples, t);
  return qp_.Solve(feet_, com_W, demand.force_W, demand.moment_W);
}

}  // namespace stairplan
