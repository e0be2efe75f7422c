#include "stairplan/simulation/convex_mpc.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

#include "stairplan/geometry/cross_matrix.h"
#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

constexpr double kGravity = 9.81;  // [m/s^2]

// Row offsets of the state's parts.
constexpr int kAttitude = 0, kPosition = 3, kAngularVelocity = 6, kVelocity = 9;

}  // namespace

void ConvexMpcSettings::Validate() const {
  if (knots < 2 || knots > 50) throw FieldError("knots", "must be in [2, 50]");
  RequireInRange("knot_dt", knot_dt, 1e-3, 0.2);
  RequireInRange("friction", friction, 0.0, 10.0);
  RequireInRange("friction_use", friction_use, 0.0, 1.0);
  RequireInRange("min_normal", min_normal, 0.0, 1e4);
  RequireInRange("attitude_weight", attitude_weight, 0.0, 1e8);
  RequireInRange("position_weight", position_weight, 0.0, 1e8);
  RequireInRange("angular_velocity_weight", angular_velocity_weight, 0.0, 1e8);
  RequireInRange("velocity_weight", velocity_weight, 0.0, 1e8);
  RequireInRange("force_weight", force_weight, 1e-12, 1e3);
}

// Variables: every knot's four forces. Rows: four friction-pyramid faces per foot and knot
// (constant), then the first knot's twelve joint torques (their map changes with the legs).
// Cost: the condensed state errors plus a little force; refilled by every Solve().
ConvexMpc::ConvexMpc(double mass, const ConvexMpcSettings& settings) : settings_(settings), mass_(mass) {
  settings_.Validate();
  if (!(mass > 0.0) || !std::isfinite(mass)) throw FieldError("mass", "must be positive");
  n_ = settings_.knots;
  const int u = kForces * n_, x = kStates * n_;
  forces_ = program_.AddVariables("foot_forces", u);
  program_.AddQuadraticCost(forces_, Eigen::MatrixXd::Identity(u, u), Eigen::VectorXd::Zero(u));
  const double mu = settings_.friction_use * settings_.friction;
  Eigen::MatrixXd pyramid = Eigen::MatrixXd::Zero(4 * 4 * n_, u);
  for (int foot = 0; foot < 4 * n_; ++foot) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int sign = 0; sign < 2; ++sign) {
        const int row = 4 * foot + 2 * axis + sign;
        pyramid(row, 3 * foot + axis) = sign == 0 ? 1.0 : -1.0;  // |f_axis| <= mu f_z
        pyramid(row, 3 * foot + 2) = -mu;
      }
    }
  }
  friction_rows_ = program_.AddLinearConstraint({{forces_, pyramid}}, Eigen::VectorXd::Constant(pyramid.rows(), -optim::kInf),
                                                Eigen::VectorXd::Zero(pyramid.rows()), "friction");
  torque_map_ = Eigen::MatrixXd::Zero(kForces, u);
  torque_lo_ = Eigen::VectorXd::Constant(kForces, -optim::kInf);
  torque_hi_ = Eigen::VectorXd::Constant(kForces, optim::kInf);
  torque_rows_ = program_.AddLinearConstraint({{forces_, torque_map_}}, torque_lo_, torque_hi_, "joint_torques");
  gamma_ = Eigen::MatrixXd::Zero(x, u);
  weighted_gamma_ = Eigen::MatrixXd::Zero(x, u);
  free_ = Eigen::VectorXd::Zero(x);
  reference_ = Eigen::VectorXd::Zero(x);
  b_ = Eigen::MatrixXd::Zero(kStates, u);
  lower_ = Eigen::VectorXd::Zero(u);
  upper_ = Eigen::VectorXd::Zero(u);
  linear_ = Eigen::VectorXd::Zero(u);
  const double weight = mass_ * kGravity;
  Eigen::Matrix<double, kStates, 1> w;
  w << Eigen::Vector3d::Constant(settings_.attitude_weight), Eigen::Vector3d::Constant(settings_.position_weight),
      Eigen::Vector3d::Constant(settings_.angular_velocity_weight), Eigen::Vector3d::Constant(settings_.velocity_weight);
  weights_ = (weight * w).replicate(n_, 1);
}

void ConvexMpc::FillDynamics(const MpcKnot* knots) {
  const double dt = settings_.knot_dt, half = 0.5 * dt * dt;
  // B_j: a force f at foot i moves the velocity by dt f / m and the angular velocity by
  // dt I^-1 (r x f), and the position and attitude by half a step of those.
  for (int j = 0; j < n_; ++j) {
    const MpcKnot& k = knots[j];
    const Eigen::Matrix3d inverse = k.inertia_W.inverse();
    const Eigen::Vector3d com = k.position_W + k.com_offset_W;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Matrix3d spin = inverse * CrossMatrix(k.feet_W[static_cast<std::size_t>(i)] - com);
      auto block = b_.block<kStates, 3>(0, kForces * j + 3 * i);
      block.middleRows<3>(kAttitude) = half * spin;
      block.middleRows<3>(kPosition) = (half / mass_) * Eigen::Matrix3d::Identity();
      block.middleRows<3>(kAngularVelocity) = dt * spin;
      block.middleRows<3>(kVelocity) = (dt / mass_) * Eigen::Matrix3d::Identity();
    }
  }
  // gamma's block (k, j) = A^(k-j) B_j: each step down a column applies A (the attitude and
  // position advance by dt times the velocities).
  for (int j = 0; j < n_; ++j) {
    gamma_.block(kStates * j, kForces * j, kStates, kForces) = b_.middleCols(kForces * j, kForces);
    for (int k = j + 1; k < n_; ++k) {
      auto above = gamma_.block(kStates * (k - 1), kForces * j, kStates, kForces);
      auto here = gamma_.block(kStates * k, kForces * j, kStates, kForces);
      here = above;
      here.middleRows(kAttitude, 3) += dt * above.middleRows(kAngularVelocity, 3);
      here.middleRows(kPosition, 3) += dt * above.middleRows(kVelocity, 3);
    }
  }
}

void ConvexMpc::FillCost(const MpcState& state, const MpcKnot* knots) {
  const double dt = settings_.knot_dt, half = 0.5 * dt * dt;
  const Eigen::Vector3d g(0.0, 0.0, -kGravity);
  // The states with no force: gravity alone, the attitude error turning with the angular
  // velocity's lead on the reference's.
  Eigen::Matrix<double, kStates, 1> x;
  x << state.attitude_error_W, state.position_W, state.angular_velocity_W, state.velocity_W;
  for (int k = 0; k < n_; ++k) {
    const Eigen::Vector3d omega = x.segment<3>(kAngularVelocity), v = x.segment<3>(kVelocity);
    x.segment<3>(kAttitude) += dt * (omega - knots[k].angular_velocity_W);
    x.segment<3>(kPosition) += dt * v + half * g;
    x.segment<3>(kVelocity) += dt * g;
    free_.segment<kStates>(kStates * k) = x;
    // x_(k+1)'s reference: knot k+1's, the last one's carried a knot on.
    const MpcKnot& r = knots[std::min(k + 1, n_ - 1)];
    const double ahead = k + 1 < n_ ? 0.0 : dt;
    auto ref = reference_.segment<kStates>(kStates * k);
    ref.segment<3>(kAttitude).setZero();
    ref.segment<3>(kPosition) = r.position_W + ahead * r.velocity_W;
    ref.segment<3>(kAngularVelocity) = r.angular_velocity_W;
    ref.segment<3>(kVelocity) = r.velocity_W;
  }
  // 0.5 U'(G'WG + rho) U + (G'W (free - ref))'U.
  weighted_gamma_.noalias() = weights_.asDiagonal() * gamma_;
  Eigen::MatrixXd& h = program_.MutableHessian();
  h.noalias() = gamma_.transpose() * weighted_gamma_;
  h.diagonal().array() += settings_.force_weight / (mass_ * kGravity);
  free_ -= reference_;
  linear_.noalias() = weighted_gamma_.transpose() * free_;
  free_ += reference_;
  program_.SetLinearCost(forces_, linear_);
}

void ConvexMpc::FillBounds(const MpcKnot* knots, const MpcMotors& motors) {
  for (int k = 0; k < n_; ++k) {
    for (int i = 0; i < 4; ++i) {
      const double most = knots[k].max_normal[static_cast<std::size_t>(i)];
      const bool stance = most > 0.0;
      const double tangential = stance ? optim::kInf : 0.0;
      const int at = kForces * k + 3 * i;
      lower_.segment<3>(at) << -tangential, -tangential, stance ? std::min(settings_.min_normal, most) : 0.0;
      upper_.segment<3>(at) << tangential, tangential, stance ? most : 0.0;
    }
  }
  program_.SetVariableBounds(forces_, lower_, upper_);
  for (int i = 0; i < 4; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const bool stance = knots[0].max_normal[s] > 0.0;
    torque_map_.block<3, 3>(3 * i, 3 * i) = stance ? motors.torque_map[s] : Eigen::Matrix3d::Zero();
    // The least push must stay feasible, or the whole QP would be: the room widens to contain it.
    const Eigen::Vector3d at_least = motors.torque_map[s] * Eigen::Vector3d(0.0, 0.0, lower_(3 * i + 2));
    torque_lo_.segment<3>(3 * i) = stance ? Eigen::Vector3d(motors.torque_lo[s].cwiseMin(at_least)) : Eigen::Vector3d::Constant(-optim::kInf);
    torque_hi_.segment<3>(3 * i) = stance ? Eigen::Vector3d(motors.torque_hi[s].cwiseMax(at_least)) : Eigen::Vector3d::Constant(optim::kInf);
  }
  program_.SetConstraintCoefficients(torque_rows_, forces_, torque_map_);
  program_.SetConstraintBounds(torque_rows_, torque_lo_, torque_hi_);
}

void ConvexMpc::Fill(const MpcState& state, const MpcKnot* knots, const MpcMotors& motors) {
  FillDynamics(knots);
  FillCost(state, knots);
  FillBounds(knots, motors);
}

bool ConvexMpc::Solve(const MpcState& state, const MpcKnot* knots, const MpcMotors& motors,
                      std::array<Eigen::Vector3d, 4>& forces_W) {
  Fill(state, knots, motors);
  solver_.Solve(program_, &result_);
  const bool ok = result_.solved();
  for (int i = 0; i < 4; ++i) {
    forces_W[static_cast<std::size_t>(i)] = ok ? Eigen::Vector3d(forces_.Of(result_.x).segment<3>(3 * i)) : Eigen::Vector3d::Zero();
  }
  return ok;
}

std::array<Eigen::Vector3d, 4> ConvexMpc::Forces(int k) const {
  if (k < 0 || k >= n_) throw std::out_of_range("ConvexMpc::Forces: knot out of range");
  std::array<Eigen::Vector3d, 4> forces{};
  for (int i = 0; i < 4; ++i) {
    forces[static_cast<std::size_t>(i)] = result_.x.size() == gamma_.cols()
                                              ? Eigen::Vector3d(forces_.Of(result_.x).segment<3>(kForces * k + 3 * i))
                                              : Eigen::Vector3d::Zero();
  }
  return forces;
}

Eigen::Matrix<double, 12, 1> ConvexMpc::Predicted(int k) const {
  if (k < 1 || k > n_) throw std::out_of_range("ConvexMpc::Predicted: knot out of range");
  const int row = kStates * (k - 1);
  Eigen::Matrix<double, 12, 1> x = free_.segment<kStates>(row);
  if (result_.x.size() == gamma_.cols()) x += gamma_.middleRows(row, kStates) * forces_.Of(result_.x);
  return x;
}

}  // namespace stairplan
