#include "planning/validation/contact_wrench_qp.h"

#include <cmath>

#include "geometry/field_error.h"

namespace stairplan {
namespace {

// Weight of |f|^2 against the squared residual [N^2]: keeps H positive definite (no proximal
// iterations) and picks the least force among equal residuals, at a residual of ~1e-6 |f|.
constexpr double kForceRegularization = 1e-6;

Eigen::Matrix3d Cross(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

}  // namespace

const char* ToString(ContactLimit limit) {
  switch (limit) {
    case ContactLimit::kNone: return "none";
    case ContactLimit::kPull: return "pull";
    case ContactLimit::kFriction: return "friction";
    case ContactLimit::kTorque: return "torque";
    case ContactLimit::kGeometry: return "geometry";
    case ContactLimit::kNotSolved: return "not_solved";
  }
  return "unknown";
}

void ContactWrenchSettings::Validate() const {
  RequireInRange("friction", friction, 0.0, 10.0);
  RequireInRange("moment_lever", moment_lever, 1e-3, 10.0);
}

// Variables: the four forces (12) and the missed wrench (6). Rows: the balance (forces minus the
// miss equal the wanted wrench), the pyramids (four rows a foot, fixed), the joint torques.
ContactWrenchQp::ContactWrenchQp(const ContactWrenchSettings& settings) : settings_(settings) {
  settings_.Validate();
  force_ = program_.AddVariables("contact_forces", 12);
  miss_ = program_.AddVariables("wrench_miss", 6);
  program_.AddQuadraticCost(force_, kForceRegularization * Eigen::MatrixXd::Identity(12, 12), Eigen::VectorXd::Zero(12));
  Eigen::VectorXd miss_weight(6);
  const double moment_weight = 1.0 / (settings_.moment_lever * settings_.moment_lever);
  miss_weight << 1.0, 1.0, 1.0, moment_weight, moment_weight, moment_weight;
  program_.AddQuadraticCost(miss_, miss_weight.asDiagonal().toDenseMatrix(), Eigen::VectorXd::Zero(6));

  balance_map_.setZero();
  for (int i = 0; i < 4; ++i) balance_map_.block<3, 3>(0, 3 * i).setIdentity();
  wanted_.setZero();
  balance_ = program_.AddLinearConstraint({{force_, balance_map_}, {miss_, -Eigen::MatrixXd::Identity(6, 6)}}, wanted_,
                                          wanted_, "balance");

  const double slope = settings_.friction / std::sqrt(2.0);
  Eigen::MatrixXd pyramid = Eigen::MatrixXd::Zero(16, 12);
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) {  // +x, -x, +y, -y: |f_t| <= slope f_z
      pyramid(4 * i + k, 3 * i + k / 2) = k % 2 == 0 ? 1.0 : -1.0;
      pyramid(4 * i + k, 3 * i + 2) = -slope;
    }
  }
  cone_ = program_.AddLinearConstraint({{force_, pyramid}}, Eigen::VectorXd::Constant(16, -optim::kInf),
                                       Eigen::VectorXd::Zero(16), "friction_pyramids");

  torque_map_.setZero();
  torque_lo_.setConstant(-optim::kInf);
  torque_hi_.setConstant(optim::kInf);
  torque_ = program_.AddLinearConstraint({{force_, torque_map_}}, torque_lo_, torque_hi_, "joint_torques");
  force_lo_.setZero();
  force_hi_.setZero();
}

const ContactWrenchResult& ContactWrenchQp::Solve(const std::array<ContactFoot, 4>& feet, const Eigen::Vector3d& com_W,
                                                  const Eigen::Vector3d& force_W, const Eigen::Vector3d& moment_W) {
  Update(feet, com_W);
  wanted_ << force_W, moment_W;
  program_.SetConstraintBounds(balance_, wanted_, wanted_);
  solver_.Solve(program_, &solution_);
  result_ = ContactWrenchResult{};
  if (!solution_.solved()) {
    result_.limit = ContactLimit::kNotSolved;
    result_.residual = std::sqrt(force_W.squaredNorm() + (moment_W / settings_.moment_lever).squaredNorm());
    return result_;
  }
  const auto miss = miss_.Of(solution_.x);
  result_.force_error_W = miss.head<3>();
  result_.moment_error_W = miss.tail<3>();
  result_.residual = std::sqrt(result_.force_error_W.squaredNorm() +
                               (result_.moment_error_W / settings_.moment_lever).squaredNorm());
  const auto forces = force_.Of(solution_.x);
  for (int i = 0; i < 4; ++i) result_.forces_W[static_cast<std::size_t>(i)] = forces.segment<3>(3 * i);
  FindLimit(feet);
  return result_;
}

void ContactWrenchQp::Update(const std::array<ContactFoot, 4>& feet, const Eigen::Vector3d& com_W) {
  for (int i = 0; i < 4; ++i) {
    const ContactFoot& foot = feet[static_cast<std::size_t>(i)];
    balance_map_.block<3, 3>(3, 3 * i) = Cross(foot.position_W - com_W);
    torque_map_.block<3, 3>(3 * i, 3 * i) = foot.stance ? foot.torque_map : Eigen::Matrix3d::Zero();
    const double free = foot.stance ? optim::kInf : 0.0;
    force_lo_.segment<3>(3 * i) << -free, -free, 0.0;
    force_hi_.segment<3>(3 * i) << free, free, free;
    torque_lo_.segment<3>(3 * i) = foot.stance ? Eigen::Vector3d(-foot.effort) : Eigen::Vector3d::Constant(-optim::kInf);
    torque_hi_.segment<3>(3 * i) = foot.stance ? foot.effort : Eigen::Vector3d::Constant(optim::kInf);
  }
  program_.SetConstraintCoefficients(balance_, force_, balance_map_);
  program_.SetConstraintCoefficients(torque_, force_, torque_map_);
  program_.SetConstraintBounds(torque_, torque_lo_, torque_hi_);
  program_.SetVariableBounds(force_, force_lo_, force_hi_);
}

// The active constraint with the largest multiplier times its row's norm: the one whose loosening
// would shrink the residual most. None of them active while the wrench is missed: the feet's
// geometry cannot give it at all.
void ContactWrenchQp::FindLimit(const std::array<ContactFoot, 4>& feet) {
  const double wanted_scale = 1.0 + wanted_.head<3>().norm() + wanted_.tail<3>().norm() / settings_.moment_lever;
  if (result_.residual <= 1e-3 * wanted_scale) return;  // the regularisation's share
  const double slope_norm = std::sqrt(1.0 + settings_.friction * settings_.friction / 2.0);
  double best = 0.0;
  const auto consider = [&](double pressure, ContactLimit limit, int foot, int joint) {
    if (pressure <= best) return;
    best = pressure;
    result_.limit = limit;
    result_.foot = foot;
    result_.joint = joint;
  };
  for (int i = 0; i < 4; ++i) {
    if (!feet[static_cast<std::size_t>(i)].stance) continue;
    consider(std::abs(solution_.bound_duals[force_.start + 3 * i + 2]), ContactLimit::kPull, i, -1);
    for (int k = 0; k < 4; ++k) {
      consider(slope_norm * std::abs(solution_.row_duals[cone_.start + 4 * i + k]), ContactLimit::kFriction, i, -1);
    }
    for (int j = 0; j < 3; ++j) {
      const double norm = torque_map_.row(3 * i + j).norm();
      consider(norm * std::abs(solution_.row_duals[torque_.start + 3 * i + j]), ContactLimit::kTorque, i, j);
    }
  }
  // The miss's own multiplier is its weighted size; a limit far below it explains nothing.
  const double miss_pressure = solution_.row_duals.segment(balance_.start, 6).lpNorm<Eigen::Infinity>();
  if (best <= 1e-3 * miss_pressure) {
    result_.limit = ContactLimit::kGeometry;
    result_.foot = -1;
    result_.joint = -1;
  }
}

}  // namespace stairplan
