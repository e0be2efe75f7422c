#include "stairplan/planning/validation/contact_wrench_check.h"

#include <algorithm>

#include <urdf_model/model.h>

#include <Eigen/Geometry>

namespace stairplan {
namespace {

constexpr double kGravityZ = -9.81;  // [m/s^2]

// A moment residual of m g times half the hip length counts as much as a force residual of m g:
// that is the lever over which the feet trade load when the COM moves along the body.
double MomentLever(const RobotModel& robot) { return std::max(0.05, 0.5 * robot.hip_length()); }

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

// The mass, centre and inertia (about that centre, base axes) of `link` and every link fixed to
// it, added into `mass`, `first` (sum m c) and `second` (sum of I + m c c^T terms, see BodyInertia).
void AddFixedLinks(const urdf::Link& link, const Eigen::Isometry3d& link_B, double& mass, Eigen::Vector3d& first,
                   Eigen::Matrix3d& second) {
  if (link.inertial && link.inertial->mass > 0.0) {
    const urdf::Inertial& in = *link.inertial;
    Eigen::Matrix3d local;
    local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Eigen::Isometry3d frame_B = link_B * ToIsometry(in.origin);
    const Eigen::Vector3d c = frame_B.translation();
    // About the base origin: I_c + m (|c|^2 1 - c c^T); recentred on the composite centre later.
    second += frame_B.linear() * local * frame_B.linear().transpose() +
              in.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    mass += in.mass;
    first += in.mass * c;
  }
  for (const urdf::LinkSharedPtr& child : link.child_links) {
    if (!child || !child->parent_joint || child->parent_joint->type != urdf::Joint::FIXED) continue;
    AddFixedLinks(*child, link_B * ToIsometry(child->parent_joint->parent_to_joint_origin_transform), mass, first, second);
  }
}

// The inertia of the base link and every link fixed to it (ANYmal's "base_inertia", sensors),
// about their common centre of mass, in base axes; false when none of them has an inertia.
bool BodyInertia(const RobotModel& robot, Eigen::Matrix3d& inertia_B) {
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (!base) return false;
  double mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d about_origin = Eigen::Matrix3d::Zero();
  AddFixedLinks(*base, Eigen::Isometry3d::Identity(), mass, first, about_origin);
  if (!(mass > 0.0)) return false;
  const Eigen::Vector3d c = first / mass;
  inertia_B = about_origin - mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return inertia_B.allFinite() && inertia_B.trace() > 0.0;
}

}  // namespace

ContactWrenchCheck::ContactWrenchCheck(const RobotKinematics& kinematics, double mass, const ContactWrenchSettings& settings)
    : kinematics_(kinematics), mass_(mass), qp_(mass, MomentLever(kinematics.robot()), settings) {
  body_inertia_known_ = BodyInertia(kinematics.robot(), inertia_B_);
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
  const Eigen::Matrix3d inertia_W = rotation * inertia_B_ * rotation.transpose();
  demand.moment_W = inertia_W * instant.rates.angular_W;
  SplitLineMoment(instant, inertia_W, demand);
  return qp_.Solve(feet_, demand);
}

void ContactWrenchCheck::SplitLineMoment(const WrenchInstant& instant, const Eigen::Matrix3d& inertia_W,
                                         WrenchDemand& demand) {
  line_ = LineSupport{};
  std::array<int, 2> legs{};
  int standing = 0;
  for (int l = 0; l < 4; ++l) {
    if (!instant.stance[static_cast<std::size_t>(l)]) continue;
    if (standing < 2) legs[static_cast<std::size_t>(standing)] = l;
    ++standing;
  }
  if (standing != 2) return;
  const Eigen::Vector3d a = instant.feet_W[static_cast<std::size_t>(legs[0])];
  const Eigen::Vector3d along = instant.feet_W[static_cast<std::size_t>(legs[1])] - a;
  if (!(along.norm() > 1e-6)) return;
  const Eigen::Vector3d u = along.normalized(), r = instant.com_W - a;
  // The feet give the force and any moment about a point of the line but the one along it.
  const double moment = u.dot(demand.moment_W + r.cross(demand.force_W));
  demand.moment_W -= moment * u;
  const Eigen::Vector3d off_line = r - r.dot(u) * u;
  line_.active = true;
  line_.pair = (1 << legs[0]) | (1 << legs[1]);
  line_.moment = moment;
  line_.inertia = u.dot(inertia_W * u) + mass_ * off_line.squaredNorm();
  // Tilting by theta about u moves the COM by theta u x r; the load (-force_W, gravity and the
  // inertial force) then turns the body further by theta u . ((u x r) x load).
  line_.stiffness = u.dot(u.cross(r).cross(-demand.force_W));
}

}  // namespace stairplan
