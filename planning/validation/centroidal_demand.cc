#include "planning/validation/centroidal_demand.h"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Geometry>
#include <urdf_model/model.h>

#include "planning/com_model.h"
#include "planning/plan_timeline.h"

namespace stairplan {
namespace {

constexpr double kGravity = 9.81;

using Motion = Eigen::Matrix<double, 5, 1>;  // x, y, z, pitch, yaw

Motion MotionAt(const std::vector<BodyState>& body, double t) {
  const BodyPose pose = BodyPoseAt(body, t);
  return (Motion() << pose.position_W, pose.pitch, pose.yaw).finished();
}

// Parallel-axis term of a point mass at r from the reference point.
Eigen::Matrix3d PointInertia(double mass, const Eigen::Vector3d& r) {
  return mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
}

}  // namespace

CentroidalModel::CentroidalModel(const RobotModel& robot, double window) : mass_(robot.total_mass()), window_(window) {
  if (!(window > 0.0)) throw std::invalid_argument("CentroidalModel: window must be positive");
  const Eigen::Vector3d com_B = ApproximateComOffset(robot);
  double leg_mass = 0.0;
  for (const LegModel& leg : robot.legs()) {
    inertia_B_ += PointInertia(leg.mass, 0.5 * (leg.hip_B + leg.foot_zero_B) - com_B);
    leg_mass += leg.mass;
  }
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (base && base->inertial) {
    const urdf::Inertial& in = *base->inertial;
    Eigen::Matrix3d local;
    local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
    in.origin.rotation.getQuaternion(qx, qy, qz, qw);
    const Eigen::Matrix3d rotation = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    const urdf::Vector3& p = in.origin.position;
    const double base_mass = std::max(0.0, mass_ - leg_mass);
    inertia_B_ += rotation * local * rotation.transpose() + PointInertia(base_mass, Eigen::Vector3d(p.x, p.y, p.z) - com_B);
  }
}

CentroidalDemand CentroidalModel::DemandAt(const std::vector<BodyState>& body, double t) const {
  CentroidalDemand demand;
  demand.force_W = Eigen::Vector3d(0.0, 0.0, mass_ * kGravity);
  if (body.size() < 2) return demand;
  // The plan's motion between samples is piecewise linear: its acceleration, impulses at the
  // samples, averaged over a triangle of half-width h (the second difference over +-h).
  const double h = window_;
  const Motion before = MotionAt(body, t - h), now = MotionAt(body, t), after = MotionAt(body, t + h);
  const Motion acceleration = (after - 2.0 * now + before) / (h * h);
  const Motion rate = (after - before) / (2.0 * h);
  demand.acceleration_W = acceleration.head<3>();
  demand.force_W += mass_ * demand.acceleration_W;

  // Angular velocity of R = Rz(yaw) Ry(pitch): yaw about z, pitch about the yawed y axis.
  const double pitch = now[3], yaw = now[4];
  const Eigen::Vector3d y_axis(-std::sin(yaw), std::cos(yaw), 0.0), x_axis(std::cos(yaw), std::sin(yaw), 0.0);
  const Eigen::Vector3d omega = rate[4] * Eigen::Vector3d::UnitZ() + rate[3] * y_axis;
  const Eigen::Vector3d omega_dot = acceleration[4] * Eigen::Vector3d::UnitZ() + acceleration[3] * y_axis +
                                    rate[4] * rate[3] * (-x_axis);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY())).toRotationMatrix();
  const Eigen::Matrix3d inertia_W = rotation * inertia_B_ * rotation.transpose();
  demand.moment_W = inertia_W * omega_dot + omega.cross(inertia_W * omega);
  return demand;
}

}  // namespace stairplan
