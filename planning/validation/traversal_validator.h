// The validator: replays a plan quasi-statically at a fine time step and proves it reachable,
// within joint limits, collision-free (legs against the stairs, contralateral legs, the body) and
// statically stable where the gait needs it, with every foot landing inside its step region.
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

namespace stairplan {

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
};
/// Returns the kind as plan.json writes it, e.g. "stair_collision".
const char* ToString(ViolationKind kind);

/// One violation found by the validator: when, which leg, what and by how much.
struct Violation {
  double t = 0.0;  ///< when [s]
  std::string leg;     ///< "LF".."RH", or "body"
  ViolationKind kind = ViolationKind::kStairCollision;  ///< what went wrong
  double value = 0.0;  ///< clearance, margin or distance that failed [m]; an acceleration [m/s^2]
  std::string detail;  ///< e.g. the link and stair part involved
};

/// What the validator checks and with what margins.
struct ValidationSettings {
  double time_step = 0.02;             ///< replay step [s]
  double min_clearance = 0.005;        ///< leg, leg-leg and body clearance needed [m]
  double min_stability_margin = 0.01;  ///< COM inside the support polygon by this much [m]
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

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The validator's verdict on a plan.
struct ValidationReport {
  bool ok = true;  ///< no violation found
  double min_clearance_m = 0.0;         ///< smallest leg/body-to-stairs or leg-to-leg clearance
  double min_stability_margin_m = 0.0;  ///< smallest COM margin over quasi-static phases
  std::vector<Violation> violations;    ///< in time order; the first is the first violation
  int samples = 0;  ///< instants replayed
};

/// Built once per robot and staircase; Validate() may be called for many plans. Not thread-safe.
/// Replays a plan and judges it: IK, joint limits, clearances, stability, step regions, body acceleration.
class TraversalValidator {
 public:
  /// Builds the robot's kinematics and collision model and the stairs' solids. Throws
  /// std::invalid_argument naming the field for bad settings.
  TraversalValidator(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                     const ValidationSettings& settings = {});

  /// Replays `plan` every time_step, checks each touchdown, and reports what it breaks.
  ValidationReport Validate(const Plan& plan);

 private:
  void CheckTouchdowns(const Plan& plan, ValidationReport& report) const;
  void CheckBodyAcceleration(const Plan& plan, ValidationReport& report) const;
  void CheckInstant(const Plan& plan, double t, ValidationReport& report);

  const Staircase& stairs_;
  const ConstrainedMap& map_;
  ValidationSettings settings_;
  std::unique_ptr<StanceChecker> checker_;
  std::unique_ptr<ComModel> com_;
};

}  // namespace stairplan
