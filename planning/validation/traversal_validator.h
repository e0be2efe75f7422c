// The validator: replays a plan at a fine time step and proves it reachable, within joint limits,
// collision-free (legs against the stairs, contralateral legs, the body), statically stable where
// the gait is quasi-static, and dynamically feasible for every gait (the stance feet can give the
// wrench the body's motion needs), with every foot landing inside its step region.
// It is our own check of our own plans; MuJoCo (planning/simulation) is the independent one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "collision/stance_check.h"
#include "geometry/constrained_map.h"
#include "geometry/staircase.h"
#include "planning/plan.h"
#include "planning/plan_timeline.h"
#include "planning/swing_trajectory.h"
#include "planning/com_model.h"
#include "planning/validation/contact_wrench_qp.h"
#include "planning/validation/missed_wrench_drift.h"

namespace stairplan {

class DynamicCheck;

/// What went wrong.
enum class ViolationKind {
  kFootOutsideStepRegion,  ///< a touchdown outside its stair's step region
  kOutOfReach,             ///< a foot no leg configuration reaches
  kJointLimits,            ///< a foot reachable only beyond a joint limit
  kStairCollision,         ///< a leg link closer to the stairs than the margin
  kLegCollision,           ///< contralateral legs closer than the margin
  kBodyCollision,          ///< the body closer to the stairs than the margin
  kStability,              ///< the centre of mass outside the support polygon (by less than the margin)
  kBodyAcceleration,       ///< a quasi-static plan's body accelerating faster than a robot can (value in m/s^2)
  /// the stance feet cannot give the wrench the motion needs within friction and torque limits
  /// (value: the residual in N; leg: the foot of the limiting constraint, "body" when geometric)
  kDynamics,
};
/// Returns the kind as plan.json writes it, e.g. "stair_collision".
const char* ToString(ViolationKind kind);

/// One violation found by the validator: when, which leg, what and by how much.
struct Violation {
  double t = 0.0;  ///< when [s]
  std::string leg;     ///< "LF".."RH", or "body"
  ViolationKind kind = ViolationKind::kStairCollision;  ///< what went wrong
  double value = 0.0;  ///< clearance, margin or distance that failed [m]; an acceleration [m/s^2]; a residual [N]
  std::string detail;  ///< e.g. the link and stair part involved
};

/// What the validator checks and with what margins.
struct ValidationSettings {
  double time_step = 0.02;             ///< replay step [s]
  double min_clearance = 0.005;        ///< leg, leg-leg and body clearance needed [m]
  double min_stability_margin = 0.01;  ///< COM inside the support polygon by this much [m]
  /// Quasi-static gaits (the crawl) need the COM inside the support polygon at all times;
  /// dynamic gaits (trot) do not: the dynamic check judges them.
  bool stability_for_dynamic_gaits = false;
  /// A quasi-static gait's body may accelerate at most this much between its samples [m/s^2]. The
  /// instants of a plan can each be fine while the body jumps between them: the posture fit's
  /// fallback of one height per instant once moved the body 18 cm in 0.1 s (37 m/s^2) at a swing's
  /// liftoff, and MuJoCo fell there. 2 g is far above what a crawl needs (the default plans ask
  /// 3-5) and far below a jump.
  double max_body_acceleration = 19.62;
  /// Check at every instant that the stance feet can give the wrench of the body's motion.
  bool check_dynamics = true;
  /// A miss of the wrench below this share of the robot's weight is none (the QP's residual).
  double max_contact_residual = 0.01;
  /// How far the body may drift from the plan over a stretch of instants whose wrench the feet
  /// miss (missed_wrench_drift.h) [m]. Plans MuJoCo executes drift up to 12 mm (Go1 on low
  /// stairs; the default climb 0.4 mm, descents 5 mm); the default climb at twice its pace 34 mm,
  /// and MuJoCo falls on it.
  double max_contact_drift = 0.02;
  /// The body's accelerations are averaged over +-this [s] (centroidal_demand.h): the spacing of
  /// a plan's body samples, whose second differences it then reads.
  double acceleration_window = 0.05;
  ContactWrenchSettings contacts;      ///< friction and the residual's moment scale
  int max_violations = 64;             ///< violations listed at most (the first ones in time)
  SwingSettings swing;                 ///< for footsteps whose plan gives no swing apex
  IkSettings ik;  ///< IK of the feet, as the planners solve it

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The validator's verdict on a plan.
struct ValidationReport {
  bool ok = true;  ///< no violation found
  double min_clearance_m = 0.0;         ///< smallest leg/body-to-stairs or leg-to-leg clearance
  double min_stability_margin_m = 0.0;  ///< smallest COM margin over quasi-static phases
  double max_contact_residual_n = 0.0;  ///< largest residual of the dynamic check [N]
  double max_contact_drift_m = 0.0;     ///< largest drift those residuals add up to [m]
  std::vector<Violation> violations;    ///< in time order; the first is the first violation
  int samples = 0;  ///< instants replayed
};

/// Built once per robot and staircase; Validate() may be called for many plans. Not thread-safe.
/// Replays a plan and judges it: IK, joint limits, clearances, stability, step regions, body
/// acceleration, dynamic feasibility.
class TraversalValidator {
 public:
  /// Builds the robot's kinematics and collision model and the stairs' solids. Throws
  /// std::invalid_argument naming the field for bad settings.
  TraversalValidator(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                     const ValidationSettings& settings = {});
  ~TraversalValidator();  ///< out of line: DynamicCheck is only declared here

  /// Replays `plan` every time_step, checks each touchdown, and reports what it breaks.
  ValidationReport Validate(const Plan& plan);

 private:
  void CheckTouchdowns(const Plan& plan, ValidationReport& report) const;
  void CheckBodyAcceleration(const Plan& plan, ValidationReport& report) const;
  void CheckInstant(const Plan& plan, double t, ValidationReport& report);
  /// Whether the stance feet have missed the motion's wrench for long enough at t to drift
  /// beyond max_contact_drift; if so `found` says by how much and why.
  bool CheckDynamics(const Plan& plan, double t, const BodyPose& body, const std::array<Eigen::Vector3d, 4>& q,
                     const std::array<Eigen::Vector3d, 4>& contacts, const std::array<bool, 4>& stance,
                     const Eigen::Vector3d& com, ValidationReport& report, Violation* found);

  const Staircase& stairs_;
  const ConstrainedMap& map_;
  ValidationSettings settings_;
  std::unique_ptr<StanceChecker> checker_;
  std::unique_ptr<ComModel> com_;
  std::unique_ptr<DynamicCheck> dynamics_;
  MissedWrenchDrift drift_;
};

}  // namespace stairplan
