#include "stairplan/simulation/stance_force_qp.h"

#include <algorithm>

#include "stairplan/geometry/cross_matrix.h"
#include "stairplan/geometry/field_error.h"

namespace stairplan {

void StanceForceSettings::Validate() const {
  RequireInRange("friction", friction, 0.0, 10.0);
  RequireInRange("friction_use", friction_use, 0.0, 1.0);
  RequireInRange("torque_use", torque_use, 0.0, 1.0);
  RequireInRange("min_normal", min_normal, 0.0, 1e4);
  RequireInRange("force_weight", force_weight, 1e-9, 1e6);
  RequireInRange("moment_weight", moment_weight, 1e-9, 1e6);
  RequireInRange("regularization", regularization, 1e-12, 1e3);
}

// Variables: the four feet's forces (12) and the wrench error (6). Rows: wrench map * f - error =
// desired wrench (equalities; the map changes with the feet), then four friction-pyramid rows per
// foot (constant). Cost: weighted error plus a little force. Swing feet get zero bounds.
StanceForceQp::StanceForceQp(const StanceForceSettings& settings) : settings_(settings) {
  settings_.Validate();
  forces_ = program_.AddVariables("foot_forces", 12);
  slack_ = program_.AddVariables("wrench_error", 6);
  program_.AddQuadraticCost(forces_, settings_.regularization * Eigen::MatrixXd::Identity(12, 12), Eigen::VectorXd::Zero(12));
  Eigen::VectorXd w(6);
  w << Eigen::Vector3d::Constant(settings_.force_weight), Eigen::Vector3d::Constant(settings_.moment_weight);
  program_.AddQuadraticCost(slack_, w.asDiagonal().toDenseMatrix(), Eigen::VectorXd::Zero(6));
  wrench_map_ = Eigen::MatrixXd::Zero(6, 12);
  for (int i = 0; i < 4; ++i) wrench_map_.block(0, 3 * i, 3, 3).setIdentity();
  wrench_ = Eigen::VectorXd::Zero(6);
  wrench_rows_ = program_.AddLinearConstraint(
      {{forces_, wrench_map_}, {slack_, -Eigen::MatrixXd::Identity(6, 6)}}, wrench_, wrench_, "wrench");
  const double mu = settings_.friction_use * settings_.friction;
  Eigen::MatrixXd pyramid = Eigen::MatrixXd::Zero(16, 12);
  for (int i = 0; i < 4; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int sign = 0; sign < 2; ++sign) {
        const int row = 4 * i + 2 * axis + sign;
        pyramid(row, 3 * i + axis) = sign == 0 ? 1.0 : -1.0;  // |f_axis| <= mu f_z
        pyramid(row, 3 * i + 2) = -mu;
      }
    }
  }
  program_.AddLinearConstraint({{forces_, pyramid}}, Eigen::VectorXd::Constant(16, -optim::kInf),
                               Eigen::VectorXd::Zero(16), "friction");
  torque_map_ = Eigen::MatrixXd::Zero(12, 12);
  torque_lo_ = Eigen::VectorXd::Constant(12, -optim::kInf);
  torque_hi_ = Eigen::VectorXd::Constant(12, optim::kInf);
  torque_rows_ = program_.AddLinearConstraint({{forces_, torque_map_}}, torque_lo_, torque_hi_, "joint_torques");
  lower_ = Eigen::VectorXd::Zero(12);
  upper_ = Eigen::VectorXd::Zero(12);
}

bool StanceForceQp::Solve(const std::array<Foot, 4>& feet, const Eigen::Vector3d& com_W, const Eigen::Vector3d& force_W,
                          const Eigen::Vector3d& moment_W, std::array<Eigen::Vector3d, 4>& forces_W) {
  for (int i = 0; i < 4; ++i) {
    const Foot& foot = feet[static_cast<std::size_t>(i)];
    const Eigen::Vector3d r = foot.position_W - com_W;
    wrench_map_.block(3, 3 * i, 3, 3) = CrossMatrix(r);  // moment of f about the COM: r x f
    const bool stance = foot.max_normal > 0.0;
    const double least = std::min(settings_.min_normal, foot.max_normal);
    const double tangential = stance ? optim::kInf : 0.0;
    lower_.segment<3>(3 * i) << -tangential, -tangential, stance ? least : 0.0;
    upper_.segment<3>(3 * i) << tangential, tangential, stance ? foot.max_normal : 0.0;
    torque_map_.block<3, 3>(3 * i, 3 * i) = stance ? foot.torque_map : Eigen::Matrix3d::Zero();
    // The least push must stay feasible, or the whole QP would be: the room widens to contain it.
    const Eigen::Vector3d at_least = foot.torque_map * Eigen::Vector3d(0.0, 0.0, least);
    if (stance) {
      torque_lo_.segment<3>(3 * i) = foot.torque_lo.cwiseMin(at_least);
      torque_hi_.segment<3>(3 * i) = foot.torque_hi.cwiseMax(at_least);
    } else {
      torque_lo_.segment<3>(3 * i).setConstant(-optim::kInf);
      torque_hi_.segment<3>(3 * i).setConstant(optim::kInf);
    }
  }
  program_.SetConstraintCoefficients(torque_rows_, forces_, torque_map_);
  program_.SetConstraintBounds(torque_rows_, torque_lo_, torque_hi_);
  program_.SetConstraintCoefficients(wrench_rows_, forces_, wrench_map_);
  wrench_ << force_W, moment_W;
  program_.SetConstraintBounds(wrench_rows_, wrench_, wrench_);
  program_.SetVariableBounds(forces_, lower_, upper_);
  solver_.Solve(program_, &result_);
  const bool ok = result_.solved();
  for (int i = 0; i < 4; ++i) {
    forces_W[static_cast<std::size_t>(i)] = ok ? Eigen::Vector3d(forces_.Of(result_.x).segment<3>(3 * i)) : Eigen::Vector3d::Zero();
  }
  return ok;
}

}  // namespace stairplan
