#include "planning/validation/contact_wrench_check.h"

#include <algorithm>

#include <urdf_model/model.h>

#include <Eigen/Geometry>

namespace stairplan {
namespace {

constexpr double kGravityZ = -9.81;  // [m/s^2]

// A moment residual of m g times half the hip length counts as much as a force residual of m g:
// that is the lever over which the feet trade load when the COM moves along the body.
double MomentLever(const RobotModel& robot) { return std::max(0.05, 0.5 * robot.hip_length()); }

// The base link's URDF inertia about its centre of mass, in base axes; false when it has none.
bool BaseInertia(const RobotModel& robot, Eigen::Matrix3d& inertia_B) {
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (!base || !base->inertial) return false;
  const urdf::Inertial& in = *base->inertial;
  Eigen::Matrix3d local;
  local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  double x = 0, y = 0, z = 0, w = 1;
  in.origin.rotation.getQuaternion(x, y, z, w);
  const Eigen::Matrix3d r = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  inertia_B = r * local * r.transpose();
  return inertia_B.allFinite() && inertia_B.trace() > 0.0;
}

}  // namespace

ContactWrenchCheck::ContactWrenchCheck(const RobotKinematics& kinematics, double mass, const ContactWrenchSettings& settings)
    : kinematics_(kinematics), mass_(mass), qp_(mass, MomentLever(kinematics.robot()), settings) {
  body_inertia_known_ = BaseInertia(kinematics.robot(), inertia_B_);
  if (!body_inertia_known_) inertia_B_.setZero();
  torque_limits_checked_ = true;
  for (int l = 0; l < 4; ++l) {
    const std::vector<JointLimits>& limits = kinematics.leg(l).model().limits;
    for (int j = 0; j < 3; ++j) {
      const double effort = j < static_cast<int>(limits.size()) ? limits[static_cast<std::size_t>(j)].effort : 0.0;
      torque_limits_checked_ = torque_limits_checked_ && effort > 0.0;
      effort_[static_cast<std::size_t>(l)](j) = effort;
    }
  }
  // One joint without a limit leaves the robot without a torque model: check none rather than some.
  if (!torque_limits_checked_) effort_.fill(Eigen::Vector3d::Constant(optim::kInf));
}

const WrenchResult& ContactWrenchCheck::Check(const WrenchInstant& instant, RobotWorkspace& ws) {
  const Eigen::Matrix3d rotation = instant.body.ToIsometry().linear();
  for (int l = 0; l < 4; ++l) {
    const auto i = static_cast<std::size_t>(l);
    WrenchFoot& foot = feet_[i];
    foot.stance = instant.stance[i];
    foot.position_W = instant.feet_W[i];
    foot.normal_W = instant.normals_W[i];
    foot.effort = effort_[i];
    // The motors hold the ground's force f on the foot: tau = -J^T R^T f (J in base axes).
    foot.torque_map = foot.stance ? Eigen::Matrix3d(-kinematics_.leg(l).FootJacobian(instant.q[i], ws.leg(l)).transpose() *
                                                    rotation.transpose())
                                  : Eigen::Matrix3d::Zero();
  }
  WrenchDemand demand;
  demand.com_W = instant.com_W;
  demand.force_W = mass_ * (instant.rates.linear_W - Eigen::Vector3d(0.0, 0.0, kGravityZ));
  demand.moment_W = rotation * inertia_B_ * rotation.transpose() * instant.rates.angular_W;
  return qp_.Solve(feet_, demand);
}

}  // namespace stairplan
