// A plan: footsteps, body trajectory and timings for one traversal of a staircase. Every planner
// produces one; the validator, the JSON and SVG writers and the simulator consume it.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan_gait.h"

namespace stairplan {

/// One touchdown of one foot. The position is the foot's contact point on the surface.
struct Footstep {
  std::string leg;            ///< "LF", "RF", "LH" or "RH"
  double t_liftoff = 0.0;     ///< when the foot leaves its previous foothold [s]
  double t_touchdown = 0.0;   ///< when it lands here [s]
  Eigen::Vector3d position_W = Eigen::Vector3d::Zero();  ///< contact point [m]
  Eigen::Vector3d from_W = Eigen::Vector3d::Zero();      ///< the foothold it left [m]
  int stair_index = -1;       ///< the surface it lands on
  bool in_step_region = false;  ///< it lands inside its stair's step region
  /// Top of the swing's contact-point path [m]; NaN: derived from the stairs (SwingTrajectory).
  double swing_apex_z = std::numeric_limits<double>::quiet_NaN();
  /// Share of the horizontal travel the foot makes low over its old foothold before it rises, in
  /// [0, 1): 0 lifts it straight up first (SwingTrajectory); more carries it under the hip to the
  /// riser first (the 2012 paper's swing: a hip barely above the upper tread cannot lift the foot
  /// behind it to the nose's height, and passes it forward below, then up).
  double swing_approach_share = 0.0;
};

/// The body (base frame origin) at one instant. Pitch is about the body's y axis, right-hand
/// rule: nose-up is negative. com_shift is the forward shift of the centre of mass [m];
/// com_shift_y its shift toward the body's left (the body QP's weight shift over the support
/// triangle) [m]. Both are already included in x and y.
struct BodyState {
  double t = 0.0;  ///< time [s]
  double x = 0.0;  ///< along travel [m]
  double y = 0.0;  ///< to the left [m]
  double z = 0.0;  ///< height [m]
  double pitch = 0.0;  ///< about y, nose-up negative [rad]
  double yaw = 0.0;  ///< heading about z [rad]
  double com_shift = 0.0;  ///< forward shift of the centre of mass [m]
  double com_shift_y = 0.0;  ///< leftward shift of the centre of mass [m]
};

/// Whether a plan was found.
enum class PlanStatus { kOk, kInfeasible };
/// Returns "ok" or "infeasible".
const char* ToString(PlanStatus status);

/// What made a plan's body trajectory.
enum class BodyPlannerKind {
  kQuasiStaticPath,     ///< the quasi-static COM path fitted to the footsteps (stairplan/planning/body_path.h)
  kRecedingHorizonQp,   ///< the receding-horizon body QP run forward cycle by cycle (stairplan/planning/body/)
  kRecedingHorizonNlp,  ///< that QP's plan refined window by window by the exact NLP
};
/// "quasi_static_path", "receding_horizon_qp", "receding_horizon_nlp".
const char* ToString(BodyPlannerKind kind);

/// How one control cycle of the receding-horizon body planner went.
enum class BodyPlanStatus {
  kOk,          ///< solved this cycle
  kStale,       ///< not solved in the cycle budget (or the solver failed): the shifted previous plan
  kInfeasible,  ///< the next knot breaks a stance leg's bound (no valid hip height there)
};
/// "ok", "stale", "infeasible".
const char* ToString(BodyPlanStatus status);

/// One cycle of the receding-horizon body planner as the offline driver ran it.
struct BodyCycleStats {
  double t = 0.0;          ///< the cycle's time [s]
  BodyPlanStatus status = BodyPlanStatus::kOk;  ///< how the cycle went
  int solves = 0;          ///< QPs solved (more than one only at warm-up)
  int iterations = 0;      ///< the QPs' active-set changes
  double solve_us = 0.0;   ///< wall time in the QP solver [us]
  double total_us = 0.0;   ///< wall time of the whole cycle, linearisation included [us]
  /// The share of its linearisation point's violations the executed knot keeps (with leg rows;
  /// BodyPlannerOutput::relaxation): above 0 the robot is knowingly sent through a broken row.
  double relaxation = 0.0;
  /// True when the executed knot keeps part of a violation (beyond the QP's own tolerance, which
  /// leaves relaxations of about 1e-15 where every row holds).
  bool relaxed() const { return relaxation > 1e-6; }
};

/// The cycles of a traversal that executed a relaxed knot (BodyCycleStats::relaxed()).
struct RelaxedCycles {
  int count = 0;         ///< how many
  double first_t = 0.0;  ///< the first one's time [s] (0 when none)
  double most = 0.0;     ///< the largest relaxation among them
};
/// Counts the relaxed cycles among `cycles`.
RelaxedCycles SummariseRelaxed(const std::vector<BodyCycleStats>& cycles);

/// How one fixed-cadence controller of the step planner fared over a traversal.
struct ControllerScore {
  double cadence_s = 0.0;         ///< swing duration [s]
  Gait gait = Gait::kCrawl;       ///< the controller's gait
  double score = 0.0;             ///< mean score over the cycles where it was admissible (inf: never)
  std::string ruled_out_reason;   ///< why it was first ruled out, "" when never
  int cycles_selected = 0;        ///< cycles in which it was chosen
  int cycles_ruled_out = 0;       ///< cycles in which a hard rule excluded it
};

/// A gait planned before the one a plan walks, and why its plan was not taken.
struct GaitRejection {
  Gait gait = Gait::kWalk;  ///< the gait tried
  std::string reason;       ///< its plan's status reason, or its first violation
};

/// A plan: footsteps, body trajectory and timings for one traversal of a staircase.
struct Plan {
  std::string robot_name;  ///< the robot's name
  std::string robot_source;  ///< where the robot came from (its file)
  std::vector<std::string> legs;              ///< leg names in the robot's order
  Facing facing = Facing::kForward;  ///< which way the body faces relative to the travel
  double cadence_s = 0.0;                     ///< swing duration of the chosen controller [s]
  std::optional<Gait> gait;  ///< the gait walked; none when no controller was chosen
  /// The hip height (share of the leg's reach) the pipeline's robot-aware map and body path were
  /// built for; validate and simulate rebuild that map from it. NaN: the pipeline's default.
  double hip_height_fraction = std::numeric_limits<double>::quiet_NaN();
  std::vector<Eigen::Vector3d> initial_feet_W;  ///< contact points at t = 0, in `legs` order
  std::vector<Footstep> footsteps;            ///< sorted by touchdown time
  std::vector<BodyState> body;                ///< sampled body trajectory
  BodyPlannerKind body_planner = BodyPlannerKind::kQuasiStaticPath;  ///< what made the body trajectory
  std::vector<BodyCycleStats> body_cycles;    ///< the receding horizon's cycles, empty for the path
  PlanStatus status = PlanStatus::kOk;  ///< ok, or infeasible (see status_reason)
  std::string status_reason;                  ///< why it is infeasible, empty when ok
  std::vector<std::pair<std::string, double>> timing_us;  ///< per stage [us]
  std::vector<ControllerScore> controllers;   ///< the step planner's controllers, empty for other planners
  int selected = -1;                          ///< index into `controllers` chosen most often, -1 when none
  /// Faster gaits planned first and not taken (the pipeline's GaitChoice::kAuto), in the order tried.
  std::vector<GaitRejection> rejected_gaits;

  /// The time of the last body sample [s].
  double duration() const { return body.empty() ? 0.0 : body.back().t; }
};

}  // namespace stairplan
