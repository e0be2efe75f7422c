// What a plan's motion asks of its contacts at an instant: the net contact force and the moment
// about the centre of mass that the body's acceleration needs, in the single-rigid-body model
// (the COM accelerates with the base origin, the angular momentum is the base's rotational inertia
// times its angular velocity; the legs' own motion is left out: they weigh a fraction of the body
// and swing one or two at a time). The plan's body moves piecewise linearly between its samples
// (plan_timeline.h), so its acceleration is a train of impulses at the samples; the demand takes
// their average over a window of +-h, the second difference (p(t+h) - 2 p(t) + p(t-h)) / h^2.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "kinematics/robot_model.h"
#include "planning/plan.h"

namespace stairplan {

/// The wrench the contacts must give at one instant.
struct CentroidalDemand {
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   ///< m (a - g) [N]
  Eigen::Vector3d moment_W = Eigen::Vector3d::Zero();  ///< rate of angular momentum about the COM [N m]
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();  ///< of the COM [m/s^2]
};

/// The robot as one rigid body: its mass and rotational inertia, and the demand of a plan's motion.
class CentroidalModel {
 public:
  /// Mass and the rotational inertia about the COM at the zero pose, from the URDF: the base link's
  /// inertia tensor plus every leg lumped halfway between its hip and its foot. `window` is h [s].
  CentroidalModel(const RobotModel& robot, double window);

  /// The demand of `body` (a plan's samples, sorted by time) at time t.
  CentroidalDemand DemandAt(const std::vector<BodyState>& body, double t) const;

  double mass() const { return mass_; }  ///< [kg]
  const Eigen::Matrix3d& inertia_B() const { return inertia_B_; }  ///< about the COM, base frame [kg m^2]

 private:
  double mass_ = 0.0;
  double window_ = 0.0;
  Eigen::Matrix3d inertia_B_ = Eigen::Matrix3d::Zero();
};

}  // namespace stairplan
