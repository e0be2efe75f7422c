// The contact-wrench QP of the validator's dynamic check: can the stance feet produce a given
// wrench on the robot (force m (a - g), moment dL/dt about the centre of mass) with forces that
// push, stay inside linearised friction cones about their surface normals, and need joint torques
// within the motors' effort limits? Solved as the least squared wrench residual over those forces,
// so an unattainable wrench gives a residual (the violation's size) instead of an infeasible QP,
// and the multipliers of the binding rows say which leg and which limit is in the way.
//
// Model-free (feet, torque maps and limits are inputs), built once for four legs and updated in
// place per instant through our own QP solver, warm-started from the previous instant's active set.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stairplan/geometry/stair_friction.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/program.h"
#include "stairplan/planning/validation/leg_id.h"

namespace stairplan {

/// What the validator does with the dynamic check.
enum class DynamicsCheckMode {
  kOff,     ///< not run
  kReport,  ///< run and summarised (ValidationReport::dynamics), not part of the verdict
  kJudge,   ///< run, and every failing leg and limit is a violation: the plan is then not ok
};
/// "off", "report", "judge".
const char* ToString(DynamicsCheckMode mode);

/// Settings of the dynamic check (the contact-wrench QP).
struct ContactWrenchSettings {
  /// Reported for the crawls, whose slow weight shifts the support polygon judges; judged for the
  /// walk and the trot (IsJudgedDynamically), whose pace it cannot. Judging the crawls would reject
  /// plans MuJoCo walks: the check holds the legs to their torque limits and the inscribed friction
  /// pyramid together, where small robots' quasi-static crawls run at their limits.
  DynamicsCheckMode mode = DynamicsCheckMode::kReport;
  /// Friction coefficient of the stairs: the MuJoCo world's too (stairplan/geometry/stair_friction.h), so
  /// that the two judges see the same ground.
  double friction = kStairFriction;
  /// Faces of the friction pyramid (at least 4). The pyramid is inscribed in the cone (its faces'
  /// coefficient is friction * cos(pi / faces)), so a force it admits the true cone admits too.
  int friction_faces = 8;
  /// The residual above which an instant fails, as a share of the robot's weight. The QP's own
  /// error (a 1e-7 force regularisation) is orders of magnitude below it.
  double residual_tolerance = 1e-3;
  /// Where two feet stand (a trot's diagonal), no force at them has a moment about the line
  /// between them, and a plan's moment about it within a hair of zero would be a plan no robot
  /// follows exactly: the check takes that moment out of the instant's wrench and integrates what
  /// it would do, the body tipping about the line (a pendulum that topples away from it), over
  /// each two-foot phase from rest. The phase fails beyond this tilt [rad]: 0.03 rad moves the
  /// swinging feet, about 0.3 m from the line, by less than the validator's 1 cm clearance margin.
  double max_line_tilt = 0.03;
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// What bound the wrench when it could not be produced.
enum class WrenchLimit {
  kNone,               ///< the wrench is produced (residual within tolerance)
  kFrictionCone,       ///< a stance foot's friction pyramid
  kTorqueLimit,        ///< a stance leg's joint torque against its effort limit
  kWrenchUnattainable, ///< the feet would have to pull (the COM outside their support) or there are none
};
/// "none", "friction_cone", "torque_limit", "wrench_unattainable".
const char* ToString(WrenchLimit limit);

/// One foot of the QP.
struct WrenchFoot {
  bool stance = false;                                    ///< carries load (a swing foot's force is zero)
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();   ///< contact point [m]
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();    ///< the surface's unit normal under it
  /// Joint torques per unit of world force on the foot: tau = torque_map f [N m / N].
  Eigen::Matrix3d torque_map = Eigen::Matrix3d::Zero();
  /// |tau_j| <= effort_j [N m]; infinity: no limit.
  Eigen::Vector3d effort = Eigen::Vector3d::Constant(optim::kInf);
};

/// The wrench the feet must produce at one instant.
struct WrenchDemand {
  Eigen::Vector3d com_W = Eigen::Vector3d::Zero();     ///< centre of mass [m]
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   ///< m (a - g) [N]
  Eigen::Vector3d moment_W = Eigen::Vector3d::Zero();  ///< dL/dt about the centre of mass [N m]
};

/// The QP's answer at one instant.
struct WrenchResult {
  bool solved = false;  ///< the QP solved (otherwise residual is the whole demand)
  /// |(force residual, moment residual / lever)| [N]: 0 when the feet produce the wrench.
  double residual = 0.0;
  bool within_tolerance = true;  ///< residual <= residual_tolerance * weight
  WrenchLimit limit = WrenchLimit::kNone;  ///< what binds, when not within tolerance
  LegId leg = LegId::kNone;  ///< the leg whose limit binds most (see ContactWrenchQp::Solve)
  std::array<Eigen::Vector3d, 4> forces_W{};  ///< ground forces on the feet [N]
};

/// The contact-wrench QP (see the file's top comment). Not thread-safe; no allocation per solve
/// after the first.
class ContactWrenchQp {
 public:
  /// `mass` [kg] sets the tolerance (a share of the weight); `lever` [m] converts a moment residual
  /// into a force (a moment error of m g lever counts as a force error of m g). Throws
  /// std::invalid_argument naming the field for bad settings, mass or lever.
  ContactWrenchQp(double mass, double lever, const ContactWrenchSettings& settings = {});

  /// The forces closest to producing `demand`. When the residual exceeds the tolerance, the binding
  /// leg is the one with the largest multiplier on its friction or torque rows: the leg whose
  /// limit, relaxed, lowers the squared residual fastest. A binding foot left with no force (its
  /// pyramid's apex) is reported as kWrenchUnattainable: it would have to pull. Throws
  /// std::invalid_argument for a non-finite input or a zero normal.
  const WrenchResult& Solve(const std::array<WrenchFoot, 4>& feet, const WrenchDemand& demand);

  /// The residual above which an instant fails [N].
  double tolerance() const { return tolerance_; }
  /// The settings it was built with.
  const ContactWrenchSettings& settings() const { return settings_; }

 private:
  void SetFoot(int leg, const WrenchFoot& foot, const WrenchDemand& demand);
  void FindBindingLeg(const std::array<WrenchFoot, 4>& feet);

  ContactWrenchSettings settings_;
  double mass_ = 0.0;
  double lever_ = 0.0;
  double tolerance_ = 0.0;
  optim::Program program_;
  optim::VariableBlock forces_, residual_;
  optim::ConstraintRows wrench_rows_, cone_rows_, torque_rows_;
  optim::ActiveSetQpSolver solver_;
  optim::SolveResult solution_;
  WrenchResult result_;
  // Sized once: the wrench map (6 x 12), the pyramids (4 faces x 12), the torque map (12 x 12), bounds.
  Eigen::MatrixXd wrench_map_, cone_map_, torque_map_;
  Eigen::VectorXd wrench_, cone_lower_, cone_upper_, torque_lower_, torque_upper_, force_lower_, force_upper_;
};

}  // namespace stairplan
