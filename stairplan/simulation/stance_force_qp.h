// The stance-force distribution of the executor: the contact forces of the stance feet that best
// give a desired wrench on the robot (force, and moment about its centre of mass), each force
// inside its friction pyramid and its motors' limits, pushing, never pulling. A small QP of our own solver, built
// once for four legs and updated in place every millisecond (foot positions, wrench, which feet
// stand and how much load each may take). Unlike a split of vertical forces alone, the moments of
// the forces along the ground (applied below the centre of mass) are part of the balance, so a
// body accelerating sideways does not roll.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/geometry/stair_friction.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/program.h"

namespace stairplan {

/// Friction, torque room and weights of the stance-force QP.
struct StanceForceSettings {
  double friction = kStairFriction;  ///< friction coefficient of the ground (the executor sets the world's)
  double friction_use = 0.7;    ///< share of the friction pyramid the forces may use
  double torque_use = 0.95;     ///< share of a motor's effort limit the forces may use
  double min_normal = 1.0;      ///< a stance foot pushes at least this much [N] (stays loaded)
  double force_weight = 1.0;    ///< weight of the force rows of the wrench error [1/N^2]
  double moment_weight = 25.0;  ///< weight of the moment rows [1/(N m)^2]: 5x a force, lever 0.2 m
  double regularization = 1e-4; ///< weight of |f|^2: least force for the same wrench
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The stance feet's contact forces that best carry the body's planned wrench: a small QP, solved
/// warm each step.
class StanceForceQp {
 public:
  /// Builds the QP once (checks `settings`: throws std::invalid_argument naming the field).
  explicit StanceForceQp(const StanceForceSettings& settings = {});

  /// One foot: where it is, how much it may push, and what its force costs its motors.
  struct Foot {
    Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  ///< the foot's contact point [m]
    double max_normal = 0.0;  ///< <= 0: the foot carries nothing (swing)
    /// Joint torques per unit of ground force on the foot (-J^T R^T, world force to joints).
    Eigen::Matrix3d torque_map = Eigen::Matrix3d::Zero();
    /// The motors' room left after the leg's other torques: torque_map f within [lo, hi] [N m]
    /// (the caller gives torque_use of the effort limits minus those torques).
    ///@{
    Eigen::Vector3d torque_lo = Eigen::Vector3d::Constant(-1e20), torque_hi = Eigen::Vector3d::Constant(1e20);
    ///@}
  };

  /// Forces (world frame) of `feet` that best give `force_W` and `moment_W` (about `com_W`). A
  /// stance foot pushes between min_normal and its max_normal, inside its friction pyramid and its
  /// motors' room (relaxed where even the least push exceeds it). Returns false (forces zero) when
  /// the QP did not solve.
  bool Solve(const std::array<Foot, 4>& feet, const Eigen::Vector3d& com_W, const Eigen::Vector3d& force_W,
             const Eigen::Vector3d& moment_W, std::array<Eigen::Vector3d, 4>& forces_W);

 private:
  StanceForceSettings settings_;
  optim::Program program_;
  optim::VariableBlock forces_, slack_;
  optim::ConstraintRows wrench_rows_, torque_rows_;
  optim::ActiveSetQpSolver solver_;
  optim::SolveResult result_;
  Eigen::MatrixXd wrench_map_;      // 6 x 12
  Eigen::MatrixXd torque_map_;      // 12 x 12, block diagonal
  Eigen::VectorXd torque_lo_, torque_hi_;
  Eigen::VectorXd wrench_, lower_, upper_;
};

}  // namespace stairplan
