#include "stairplan/simulation/torque_residual.h"

#include <mujoco/mujoco.h>

namespace stairplan {

TorqueResidual::TorqueResidual(const mjModel* m, const mjData* d)
    : mass_(static_cast<std::size_t>(m->nv * m->nv), 0.0),
      qvel_prev_(Eigen::Map<const Eigen::VectorXd>(d->qvel, m->nv)),
      qacc_(Eigen::VectorXd::Zero(m->nv)),
      external_(Eigen::VectorXd::Zero(m->nv)) {}

void TorqueResidual::Update(const mjModel* m, const mjData* d) {
  const int nv = m->nv;
  const Eigen::Map<const Eigen::VectorXd> qvel(d->qvel, nv);
  qacc_ = (qvel - qvel_prev_) / m->opt.timestep;
  qvel_prev_ = qvel;
  mj_fullM(m, mass_.data(), d->qM);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> mass(mass_.data(), nv, nv);
  external_.noalias() = mass * qacc_;
  // MuJoCo's Euler step takes joint damping implicitly: (M + h D) qdd = forces.
  for (int i = 0; i < nv; ++i) {
    external_(i) += m->opt.timestep * m->dof_damping[i] * qacc_(i) + d->qfrc_bias[i] - d->qfrc_actuator[i] - d->qfrc_passive[i];
  }
  // A joint on its stop is the robot's own doing, not an impact: its model knows its stops.
  const bool sparse = mj_isSparse(m) != 0;
  for (int r = 0; r < d->nefc; ++r) {
    if (d->efc_type[r] != mjCNSTR_LIMIT_JOINT) continue;
    if (sparse) {
      for (int k = d->efc_J_rowadr[r]; k < d->efc_J_rowadr[r] + d->efc_J_rownnz[r]; ++k) {
        external_(d->efc_J_colind[k]) -= d->efc_J[k] * d->efc_force[r];
      }
    } else {
      for (int c = 0; c < nv; ++c) external_(c) -= d->efc_J[r * nv + c] * d->efc_force[r];
    }
  }
}

}  // namespace stairplan
