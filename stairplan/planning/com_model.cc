#include "stairplan/planning/com_model.h"

#include <urdf_model/model.h>

namespace stairplan {

ComModel::ComModel(const RobotKinematics& kinematics) : kinematics_(kinematics) {
  const RobotModel& robot = kinematics.robot();
  double leg_mass = 0.0;
  for (int l = 0; l < kinematics.leg_count(); ++l) {
    const LegKinematics& leg = kinematics.leg(l);
    std::vector<Part> parts;
    for (int s = 0; s < leg.segment_count(); ++s) {
      const urdf::LinkConstSharedPtr link = robot.urdf().getLink(leg.segment_link(s));
      if (!link || !link->inertial || link->inertial->mass <= 0.0) continue;
      const urdf::Vector3& p = link->inertial->origin.position;
      parts.push_back({s, link->inertial->mass, Eigen::Vector3d(p.x, p.y, p.z)});
      leg_mass += link->inertial->mass;
    }
    legs_.push_back(parts);
  }
  total_mass_ = robot.total_mass();
  base_mass_ = std::max(0.0, total_mass_ - leg_mass);
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (base && base->inertial) {
    const urdf::Vector3& p = base->inertial->origin.position;
    base_com_B_ = {p.x, p.y, p.z};
  }
}

Eigen::Vector3d ComModel::Com(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& q, RobotWorkspace& ws) const {
  Eigen::Vector3d sum_B = base_mass_ * base_com_B_;
  double mass = base_mass_;
  for (int l = 0; l < kinematics_.leg_count() && l < 4; ++l) {
    const std::vector<Eigen::Isometry3d>& frames =
        kinematics_.leg(l).LinkFrames(q[static_cast<std::size_t>(l)], ws.leg(l));
    for (const Part& part : legs_[static_cast<std::size_t>(l)]) {
      sum_B += part.mass * (frames[static_cast<std::size_t>(part.segment)] * part.com_local);
      mass += part.mass;
    }
  }
  return body.ToIsometry() * (mass > 0.0 ? Eigen::Vector3d(sum_B / mass) : Eigen::Vector3d::Zero());
}

Eigen::Vector3d ApproximateComOffset(const RobotModel& robot) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (const LegModel& leg : robot.legs()) {
    sum += leg.mass * leg.hip_B;
    mass += leg.mass;
  }
  // Everything not in a leg is lumped at the base link's own centre of mass.
  const double base_mass = std::max(0.0, robot.total_mass() - mass);
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (base && base->inertial) {
    const urdf::Vector3& p = base->inertial->origin.position;
    sum += base_mass * Eigen::Vector3d(p.x, p.y, p.z);
  }
  return mass + base_mass > 0.0 ? Eigen::Vector3d(sum / (mass + base_mass)) : Eigen::Vector3d::Zero();
}

}  // namespace stairplan
