// The executor's convex MPC (Di Carlo, Wensing, Katz, Bledt, Kim, "Dynamic Locomotion in the MIT
// Cheetah 3 Through Convex Model-Predictive Control", IROS 2018): the body as a single rigid body,
// its dynamics linearised about the plan's attitude, the stance feet's ground forces over a short
// horizon as the decision variables, each inside its linearised friction cone; the first knot's
// forces also within the motors' room. Where two feet stand (a trot's diagonal) no force gives a
// moment about the line between them, and an instantaneous distribution can only trade the body's
// attitude against its position now; over a horizon the forces plan that trade across the next
// four-feet phase.
//
// Condensed: the states are eliminated (x_k = A^k x_0 + sum A^(k-1-j) (B_j u_j + d_j)), so the QP
// has the forces alone (12 per knot) and its Hessian changes every solve with the feet's lever
// arms. Built once; Solve() refills it in place and re-solves warm through our own active-set
// solver, without allocating after the first solve.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/geometry/stair_friction.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/program.h"

namespace stairplan {

/// Horizon, friction and weights of the convex MPC.
struct ConvexMpcSettings {
  int knots = 10;               ///< knots over the horizon
  double knot_dt = 0.04;        ///< time between knots [s]
  double friction = kStairFriction;  ///< friction coefficient of the ground
  double friction_use = 0.7;    ///< share of the friction pyramid the forces may use
  double min_normal = 1.0;      ///< a loaded stance foot pushes at least this much [N]
  ///@{
  /// Weights of the state's errors from the reference, per knot: attitude [1/rad^2], position
  /// [1/m^2], angular velocity [s^2/rad^2] and velocity [s^2/m^2], each times the robot's weight
  /// so that one setting suits light and heavy robots; and of the forces [1/N^2], also scaled.
  double attitude_weight = 200.0;
  double position_weight = 400.0;
  double angular_velocity_weight = 1.0;
  double velocity_weight = 10.0;
  double force_weight = 1e-4;
  ///@}
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The body's state: position and attitude relative to the reference (world frame), velocities.
struct MpcState {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  ///< the body's reference point (base) [m]
  /// The rotation from the reference attitude to the body's, as a world-frame rotation vector [rad].
  Eigen::Vector3d attitude_error_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();          ///< [m/s]
  Eigen::Vector3d angular_velocity_W = Eigen::Vector3d::Zero();  ///< [rad/s]
};

/// One knot of the horizon: where the body should be and which feet stand where.
struct MpcKnot {
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();          ///< reference position [m]
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();          ///< reference velocity [m/s]
  Eigen::Vector3d angular_velocity_W = Eigen::Vector3d::Zero();  ///< reference angular velocity [rad/s]
  /// From the reference point to the centre of mass [m]: the forces' lever arms start there.
  Eigen::Vector3d com_offset_W = Eigen::Vector3d::Zero();
  /// The body's inertia about its centre of mass in world axes at the reference attitude [kg m^2].
  Eigen::Matrix3d inertia_W = Eigen::Matrix3d::Identity();
  std::array<Eigen::Vector3d, 4> feet_W{};  ///< contact points [m]
  /// The most each foot may push [N]; <= 0: in the air.
  std::array<double, 4> max_normal{};
};

/// The first knot's motors: joint torques per unit of ground force and the room they leave (by
/// default none: no torque bounds the forces).
struct MpcMotors {
  std::array<Eigen::Matrix3d, 4> torque_map = Filled<Eigen::Matrix3d>(Eigen::Matrix3d::Zero());  ///< tau = torque_map f (-J^T R^T)
  ///@{
  /// The room [N m].
  std::array<Eigen::Vector3d, 4> torque_lo = Filled<Eigen::Vector3d>(Eigen::Vector3d::Constant(-optim::kInf));
  std::array<Eigen::Vector3d, 4> torque_hi = Filled<Eigen::Vector3d>(Eigen::Vector3d::Constant(optim::kInf));
  ///@}

 private:
  template <typename T>
  static std::array<T, 4> Filled(const T& value) {
    return {value, value, value, value};
  }
};

/// The convex MPC (see the file's top comment).
class ConvexMpc {
 public:
  /// `mass` [kg] of the whole robot. Throws std::invalid_argument naming the field.
  ConvexMpc(double mass, const ConvexMpcSettings& settings = {});

  /// The forces over the horizon from `state` along `knots` (settings().knots of them, the first
  /// at the current instant) with `motors` at the first knot; the first knot's forces into
  /// `forces_W`. False (forces zero) when the QP did not solve.
  bool Solve(const MpcState& state, const MpcKnot* knots, const MpcMotors& motors, std::array<Eigen::Vector3d, 4>& forces_W);

  /// Fills the QP for `state`, `knots` and `motors` without solving it (Solve() does both): for
  /// benchmarks that solve it with other solvers.
  void Fill(const MpcState& state, const MpcKnot* knots, const MpcMotors& motors);
  /// The QP of the last Fill() or Solve().
  const optim::Program& program() const { return program_; }
  /// The same, for a benchmark's solvers (which keep their warm starts in it).
  optim::Program* mutable_program() { return &program_; }
  /// The state the forces of the last Solve() predict at knot k (1 .. knots) as (attitude error,
  /// position, angular velocity, velocity).
  Eigen::Matrix<double, 12, 1> Predicted(int k) const;
  /// Knot k's forces (0 .. knots - 1) from the last Solve(); zero before one [N].
  std::array<Eigen::Vector3d, 4> Forces(int k) const;
  /// The settings it was built with.
  const ConvexMpcSettings& settings() const { return settings_; }

  /// States per knot (attitude error, position, angular velocity, velocity).
  static constexpr int kStates = 12;
  /// Forces per knot (four feet).
  static constexpr int kForces = 12;

 private:
  void FillDynamics(const MpcKnot* knots);
  void FillCost(const MpcState& state, const MpcKnot* knots);
  void FillBounds(const MpcKnot* knots, const MpcMotors& motors);

  ConvexMpcSettings settings_;
  double mass_ = 0.0;
  int n_ = 0;  // knots
  optim::Program program_;
  optim::VariableBlock forces_;
  optim::ConstraintRows friction_rows_, torque_rows_;
  optim::ActiveSetQpSolver solver_;
  optim::SolveResult result_;
  // Condensed dynamics: X = free_ + gamma_ U, X = (x_1 .. x_N), sized once.
  Eigen::MatrixXd gamma_;     // 12N x 12N, block (k, j) = A^(k-j) B_j for j <= k
  Eigen::VectorXd free_;      // 12N: the states with no force
  Eigen::MatrixXd b_;         // 12 x 12N: B_j side by side
  Eigen::VectorXd weights_;   // 12N: Q's diagonal
  Eigen::VectorXd reference_; // 12N
  Eigen::MatrixXd weighted_gamma_;  // Q gamma
  Eigen::VectorXd lower_, upper_, torque_lo_, torque_hi_, linear_;
  Eigen::MatrixXd torque_map_;  // 12 x 12N: the first knot's
};

}  // namespace stairplan
