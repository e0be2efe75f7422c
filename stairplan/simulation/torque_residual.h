// External joint torques as a robot without contact sensors estimates them: the torques its motors
// applied against those its own dynamic model predicts for the motion it measured,
//   tau_ext = (M(q) + dt D) qdd + h(q, qd) - tau_motor - tau_passive,
// with qdd differentiated from measured joint and base velocities (encoders and IMU), and dt D the
// joint damping the integrator takes implicitly, less the torques of joints on their stops. Without
// contact the residual is zero; a contact on a leg shows as that contact's J^T f on the leg's
// joints. Sized once; no allocation per step.
#pragma once

#include <vector>

#include <Eigen/Core>

struct mjModel_;
struct mjData_;

namespace stairplan {

/// The external joint torques a robot without contact sensors estimates from its own dynamics (see
/// the file's top comment).
class TorqueResidual {
 public:
  /// Sized for `m`; starts from the velocities in `d`.
  TorqueResidual(const mjModel_* m, const mjData_* d);

  /// Call after every mj_step: MuJoCo then holds the mass matrix, bias, passive and motor torques
  /// of the state the step started from, and the velocities it ended with.
  void Update(const mjModel_* m, const mjData_* d);

  /// The external torque on degree of freedom `dof` [N m].
  double at(int dof) const { return external_(dof); }

 private:
  std::vector<double> mass_;  // nv x nv
  Eigen::VectorXd qvel_prev_, qacc_, external_;
};

}  // namespace stairplan
