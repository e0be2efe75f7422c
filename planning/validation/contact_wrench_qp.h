// Whether the stance feet can give a wrench: the per-instant QP of the validator's dynamic check.
// The contact forces f_i (world frame) that come closest to a wanted net force and moment about
// the centre of mass, each inside its friction cone (linearised: the pyramid inscribed in it, so
// a force it admits no cone refuses) and pushing only, with the joint torques that hold it
// (tau = -J^T f) within the leg's effort limits. The wrench they miss is the residual: zero when
// the motion is feasible. Normals are world-up: the validator's feet stand on treads.
//
// For a quasi-static instant (the wrench is the weight, no moment) on level contacts this is the
// support-polygon test: pushing forces whose moment about the COM vanishes put the COM over a
// convex combination of the feet. On treads of different heights friction can brace the feet
// against each other, so the feasible region reaches a little beyond the polygon.
//
// Built once, updated in place each instant (foot positions, torque maps, which feet stand); our
// active-set solver keeps its factorisation, so a solve allocates nothing after the first.
#pragma once

#include <array>

#include <Eigen/Core>

#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/program.h"

namespace stairplan {

/// Settings of the dynamic check's contact-force QP.
struct ContactWrenchSettings {
  /// Friction coefficient between a foot and a tread; the pyramid uses mu / sqrt(2) per axis.
  double friction = 0.6;
  /// A moment residual of 1 N m weighs as a force residual of 1 / moment_lever N [m].
  double moment_lever = 0.1;
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// One foot of the instant.
struct ContactFoot {
  bool stance = false;                                   ///< swing feet carry nothing
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  ///< contact point [m]
  /// Joint torques per unit of world force on the foot, -J^T R^T [N m / N = m].
  Eigen::Matrix3d torque_map = Eigen::Matrix3d::Zero();
  /// The joints' effort limits [N m]; infinity: none.
  Eigen::Vector3d effort = Eigen::Vector3d::Constant(optim::kInf);
};

/// The constraint that keeps the feet from giving the wrench (the one with the largest scaled
/// multiplier at the solution).
enum class ContactLimit {
  kNone,       ///< the wrench is given
  kPull,       ///< a stance foot would have to pull on its tread
  kFriction,   ///< a foot would slip: its force leaves the friction pyramid
  kTorque,     ///< a joint would exceed its effort limit
  kGeometry,   ///< no force at these feet has that moment (e.g. about the line of two feet)
  kNotSolved,  ///< the QP did not solve (should not happen: it is always feasible)
};
/// "none", "pull", "friction", "torque", "geometry", "not_solved".
const char* ToString(ContactLimit limit);

/// The answer for one instant. Forces and the error are valid until the next Solve().
struct ContactWrenchResult {
  /// The wrench missed, weighted: sqrt(|force error|^2 + (|moment error| / moment_lever)^2) [N].
  double residual = 0.0;
  Eigen::Vector3d force_error_W = Eigen::Vector3d::Zero();   ///< given minus wanted [N]
  Eigen::Vector3d moment_error_W = Eigen::Vector3d::Zero();  ///< given minus wanted [N m]
  std::array<Eigen::Vector3d, 4> forces_W{};                 ///< per foot [N]
  ContactLimit limit = ContactLimit::kNone;  ///< what keeps the feet from the wrench
  int foot = -1;   ///< the foot of `limit` (index into the feet), -1 for kNone/kGeometry
  int joint = -1;  ///< the joint of a kTorque limit (0 hip ab/adduction .. 2 knee), else -1
};

/// The per-instant QP: the four feet's forces closest to a wanted wrench, and what limits them.
class ContactWrenchQp {
 public:
  /// Builds the program once (18 variables, 34 rows). Throws std::invalid_argument naming a bad setting.
  explicit ContactWrenchQp(const ContactWrenchSettings& settings = {});

  /// The forces of `feet` closest to the net force `force_W` and moment `moment_W` (about
  /// `com_W`), and what limits them.
  const ContactWrenchResult& Solve(const std::array<ContactFoot, 4>& feet, const Eigen::Vector3d& com_W,
                                   const Eigen::Vector3d& force_W, const Eigen::Vector3d& moment_W);

  /// The next solve starts cold (no active set, H refactorised): for benchmarks' cold regime.
  void ResetWarmStart() { solver_.ResetWarmStart(); }

  const ContactWrenchSettings& settings() const { return settings_; }  ///< as validated

 private:
  void Update(const std::array<ContactFoot, 4>& feet, const Eigen::Vector3d& com_W);
  void FindLimit(const std::array<ContactFoot, 4>& feet);

  ContactWrenchSettings settings_;
  optim::Program program_;
  optim::VariableBlock force_, miss_;
  optim::ConstraintRows balance_, cone_, torque_;
  optim::ActiveSetQpSolver solver_;
  optim::SolveResult solution_;
  ContactWrenchResult result_;
  Eigen::Matrix<double, 6, 12> balance_map_;  // [sum f; sum (p - com) x f]
  Eigen::Matrix<double, 12, 12> torque_map_;  // block diagonal
  Eigen::Matrix<double, 12, 1> torque_lo_, torque_hi_, force_lo_, force_hi_;
  Eigen::Matrix<double, 6, 1> wanted_;
};

}  // namespace stairplan
