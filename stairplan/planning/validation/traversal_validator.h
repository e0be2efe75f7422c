// The validator: replays a plan at a fine time step and proves it reachable, within joint limits,
// collision-free (legs against the stairs, contralateral legs, the body), statically stable where
// the gait needs it and dynamically feasible (contact forces in friction cones within the motors'
// effort limits produce the body's motion: ContactWrenchCheck), with every foot landing inside its
// step region.
// It is our own check of our own plans; MuJoCo (stairplan/planning/simulation) is the independent one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/swing_trajectory.h"
#include "stairplan/planning/validity_margins.h"
#include "stairplan/planning/com_model.h"
#include "stairplan/planning/validation/contact_wrench_check.h"
#include "stairplan/planning/validation/leg_id.h"

namespace stairplan {

/// What went wrong.
enum class ViolationKind {
  kFootOutsideStepRegion,  ///< a touchdown outside its stair's step region
  kOutOfReach,             ///< a foot no leg configuration reaches
  kJointLimits,            ///< a foot reachable only beyond a joint limit
  kStairCollision,         ///< a leg link closer to the stairs than the margin
  kLegCollision,           ///< two neighbouring legs (LF/RF, LH/RH, LF/LH, RF/RH) closer than the margin
  kBodyCollision,          ///< the body closer to the stairs than the margin
  kStability,              ///< the centre of mass outside the support polygon (by less than the margin)
  kBodyAcceleration,       ///< a quasi-static plan's body accelerating faster than a robot can (value in m/s^2)
  kFrictionCone,           ///< dynamics: a stance foot's friction pyramid binds (value: wrench residual [N])
  kTorqueLimit,            ///< dynamics: a stance leg's effort limit binds (value: wrench residual [N])
  kWrenchUnattainable,     ///< dynamics: the feet would have to pull, or none stands (value: wrench residual [N])
  /// dynamics: on two feet, the moment about the line between them that they cannot give tips the
  /// body beyond ContactWrenchSettings::max_line_tilt within the phase (value: the tilt [rad])
  kSupportLineTilt,
};
/// Returns the kind as plan.json writes it, e.g. "stair_collision".
const char* ToString(ViolationKind kind);

/// The validator's families of checks, each a question about the plan.
enum class CheckFamily {
  kStepRegions,  ///< every touchdown inside its step region
  kKinematics,   ///< every foot reachable within the joint limits
  kCollision,    ///< legs, leg pairs and the body clear of the stairs and of each other
  kStability,    ///< a quasi-static gait's COM inside its support polygon
  kBodyAcceleration,  ///< a quasi-static gait's body accelerating no faster than a robot can
  kDynamics,     ///< the body's motion produced by contact forces in friction cones within effort limits
};
/// "step_regions", "kinematics", "collision", "stability", "body_acceleration", "dynamics".
const char* ToString(CheckFamily family);
/// The family a kind of violation belongs to.
CheckFamily FamilyOf(ViolationKind kind);

/// One violation found by the validator: when, which leg, what and by how much.
struct Violation {
  double t = 0.0;  ///< when [s]
  std::string leg;     ///< "LF".."RH", or "body"
  ViolationKind kind = ViolationKind::kStairCollision;  ///< what went wrong
  double value = 0.0;  ///< clearance, margin or distance that failed [m]; an acceleration [m/s^2]
  std::string detail;  ///< e.g. the link and stair part involved
  LegId leg_id = LegId::kNone;  ///< the leg, when one leg is meant (kNone for the body and leg pairs)
  /// The worst value of this leg and kind over the replay, in value's unit, and when: a check
  /// that fails over a stretch lists its first instant, which may be the smallest breach.
  double worst = 0.0;
  double t_worst = 0.0;  ///< [s]
};
/// True for the kinds whose value grows with the breach (a miss, an excess, a residual); false
/// for clearances and margins, which shrink.
bool LargerIsWorse(ViolationKind kind);

/// What the validator checks and with what margins.
struct ValidationSettings {
  double time_step = 0.02;             ///< replay step [s]
  double min_clearance = 0.005;        ///< leg, leg-leg and body clearance needed [m]
  double min_stability_margin = kValidStabilityMargin;  ///< COM inside the support polygon by this much [m]
  /// Quasi-static gaits (the crawl) need the COM inside the support polygon at all times;
  /// dynamic gaits (trot) do not, and are only reported.
  bool stability_for_dynamic_gaits = false;
  /// A quasi-static gait's body may accelerate at most this much between its samples [m/s^2]. The
  /// instants of a plan can each be fine while the body jumps between them: the posture fit's
  /// fallback of one height per instant once moved the body 18 cm in 0.1 s (37 m/s^2) at a swing's
  /// liftoff, and MuJoCo fell there. 2 g is far above what a crawl needs (the default plans ask
  /// 3-5) and far below a jump.
  double max_body_acceleration = 19.62;
  int max_violations = 64;             ///< violations listed at most (the first ones in time)
  SwingSettings swing;                 ///< for footsteps whose plan gives no swing apex
  IkSettings ik;  ///< IK of the feet, as the planners solve it
  ContactWrenchSettings dynamics;  ///< the dynamic check: friction, pyramid faces, residual tolerance

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
  /// Sets a numeric field by name: "friction", "friction_faces", "residual_tolerance" and
  /// "dynamics" (0 off, 1 report, 2 judge) of the dynamic check, or "time_step", "min_clearance",
  /// "min_stability_margin", "max_body_acceleration". Throws std::invalid_argument naming an
  /// unknown field or a bad value.
  void Set(const std::string& name, double value);
};

/// The dynamic check's summary over a plan.
struct DynamicsReport {
  DynamicsCheckMode mode = DynamicsCheckMode::kOff;  ///< off, reported, or part of the verdict
  bool torque_limits_checked = false;  ///< the URDF gives every joint an effort limit
  bool body_inertia_known = false;     ///< the base (or a link fixed to it) has a URDF inertia (else dL/dt = 0)
  double friction = 0.0;               ///< the friction coefficient it assumed
  double tolerance_n = 0.0;            ///< residual above which an instant fails [N]
  double max_residual_n = 0.0;         ///< largest wrench residual over the instants [N]
  double max_residual_t = 0.0;         ///< when it occurred [s]
  int failed_instants = 0;             ///< instants whose residual exceeds the tolerance
  double first_failure_t = 0.0;        ///< the first of them [s]
  ViolationKind first_failure_kind = ViolationKind::kWrenchUnattainable;  ///< what bound there
  LegId first_failure_leg = LegId::kNone;  ///< which leg bound there
  /// The largest tilt about a two-foot support line over the plan's two-foot phases [rad], and when.
  double max_line_tilt_rad = 0.0;
  double max_line_tilt_t = 0.0;  ///< [s]
};

/// The validator's verdict on a plan.
struct ValidationReport {
  bool ok = true;  ///< no violation found
  double min_clearance_m = 0.0;         ///< smallest leg/body-to-stairs or leg-to-leg clearance
  double min_stability_margin_m = 0.0;  ///< smallest COM margin over quasi-static phases
  std::vector<Violation> violations;    ///< in time order; the first is the first violation
  int samples = 0;  ///< instants replayed
  DynamicsReport dynamics;  ///< the dynamic check's summary
};

/// Built once per robot and staircase; Validate() may be called for many plans. Not thread-safe.
/// Replays a plan and judges it: IK, joint limits, clearances, stability, step regions, body acceleration, dynamics.
class TraversalValidator {
 public:
  /// Builds the robot's kinematics and collision model and the stairs' solids. Throws
  /// std::invalid_argument naming the field for bad settings. Keeps references to `stairs` and
  /// `map`, which must outlive it (temporaries are refused at compile time).
  TraversalValidator(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                     const ValidationSettings& settings = {});
  TraversalValidator(const RobotModel&, Staircase&&, const ConstrainedMap&, const ValidationSettings& = {}) = delete;
  TraversalValidator(const RobotModel&, const Staircase&, ConstrainedMap&&, const ValidationSettings& = {}) = delete;
  /// The same on the robot's kinematics built already (copied: building them is the costly part).
  TraversalValidator(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                     const ValidationSettings& settings = {});
  TraversalValidator(const RobotKinematics&, Staircase&&, const ConstrainedMap&, const ValidationSettings& = {}) = delete;
  TraversalValidator(const RobotKinematics&, const Staircase&, ConstrainedMap&&, const ValidationSettings& = {}) = delete;

  /// Replays `plan` every time_step, checks each touchdown, and reports what it breaks.
  ValidationReport Validate(const Plan& plan);

 private:
  void CheckTouchdowns(const Plan& plan, ValidationReport& report) const;
  void CheckBodyAcceleration(const Plan& plan, ValidationReport& report) const;
  void CheckInstant(const Plan& plan, double t, ValidationReport& report);
  // The dynamic check at one instant, from the stance result's joint angles.
  void CheckDynamics(const Plan& plan, double t, const StanceResult& stance_result, const std::array<Eigen::Vector3d, 4>& contacts,
                     const std::array<bool, 4>& stance, ValidationReport& report);
  // The tilt about the two-foot support line at t (wrench_'s last check), integrated from rest
  // since the phase began; a violation beyond max_line_tilt.
  void CheckLineTilt(double t, ValidationReport& report);

  const Staircase& stairs_;
  const ConstrainedMap& map_;
  ValidationSettings settings_;
  std::unique_ptr<StanceChecker> checker_;
  std::unique_ptr<ComModel> com_;
  std::unique_ptr<ContactWrenchCheck> wrench_;
  WrenchInstant instant_;  // reused by every instant
  // The dynamic check's mode for the plan being validated (settings' mode, judged for the gaits
  // that need it).
  DynamicsCheckMode dynamics_mode_ = DynamicsCheckMode::kReport;
  // The two-foot phase being integrated: its pair (0: none), the tilt and its rate, the last instant.
  int line_pair_ = 0;
  double tilt_ = 0.0, tilt_rate_ = 0.0, tilt_t_ = 0.0;
};

}  // namespace stairplan
