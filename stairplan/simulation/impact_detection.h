// How the executor tells impacts apart (US 2020/0324412 A1 ("Robotically negotiating stairs")
// [0053]-[0068]): a swing foot's external force (from the torque residual or from MuJoCo's contact
// forces) classified by its direction against the swing and by the stage of the swing; a leg link
// other than the foot classified by what it hit.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "stairplan/planning/impact/impact_response.h"
#include "stairplan/simulation/impact_record.h"

namespace stairplan {

/// How the executor detects impacts and whether it answers them.
struct ImpactDetectionSettings {
  /// How impacts are detected: torque residual, contact list or none.
  ImpactSource source = ImpactSource::kTorqueResidual;
  bool respond = true;             ///< carry the responses out (false: detect and record only)
  /// An external force at a swing foot above this share of the robot's weight is an impact.
  double force_threshold = 0.08;
  /// Foot contacts before this swing phase are a liftoff scuff (US 2020/0324412 [0067]).
  double scuff_phase = 0.12;
  /// A re-lifted swing lasts at least this long [s, plan time].
  double min_reswing_time = 0.3;
  /// A foot force with the swing foot this close to another leg's shank (beyond the two radii) is
  /// a strike on that leg, not a trip [m].
  double leg_strike_distance = 0.03;
  /// An upward foot force from the touchdown phase on is a touchdown only with the foot at most this
  /// far above the stairs; higher, it pushes on another leg (a strike) [m].
  double touchdown_clearance = 0.01;
  /// The residual's foot force is taken as a foot impact only with the foot within this of the
  /// stairs (above them, or this far either way along its swing); farther, it is a knee or thigh [m].
  double near_stairs = 0.04;
  /// A foot down outside the step region hops into it in this long [s, plan time]: the plan expects
  /// the leg to take load, and a full re-swing leaves the body on three legs too long.
  double hop_time = 0.15;
  /// How far a tripped foot draws back before it lifts again [m].
  double retract_distance = 0.02;
  /// The responses' own settings. "Early" in swing is before the foot starts lowering onto its
  /// target (the swing's last quarter): until then a trip is lifted over, after it the foot goes down.
  ImpactSettings response = [] {
    ImpactSettings s;
    s.early_swing_phase = 0.75;
    return s;
  }();

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The kind of a swing foot's impact from its external force `force_W` (the force the world puts
/// on the foot), the swing's horizontal direction `swing_dir_W`, its phase, and the phase from
/// which a contact can be a touchdown; nothing when the force is below `threshold_n`. Upward
/// forces from the touchdown phase on are a touchdown, forces at the start of the swing a scuff,
/// and the rest (the foot pushed back or down before it may land) a trip.
std::optional<ImpactKind> ClassifySwingFootForce(const Eigen::Vector3d& force_W, const Eigen::Vector3d& swing_dir_W,
                                                 double phase, double touchdown_phase, double threshold_n,
                                                 double scuff_phase);

/// The kind of a contact of a leg link other than the foot with the stairs: a knee behind its hip
/// (along the body's heading) hit something behind the body (US 2020/0324412 [0058]); otherwise it
/// glanced the terrain (US 2020/0324412 [0068]).
ImpactKind ClassifyLegLinkOnStairs(const Eigen::Vector3d& contact_W, const Eigen::Vector3d& hip_W, double body_yaw);

/// Distance from point `p` to the segment from `a` to `b` [m]: a swing foot against another leg's
/// shank (knee to foot), the robot's own kinematics telling a leg strike from a trip.
double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Whether a foot's contact point `p_W` stands in a step region of `map`: within 2 cm of the height
/// of the stair under it and inside that stair's step region. The executor's landing judge and its
/// misplaced-touchdown detector ask the same question.
bool InStepRegionAt(const ConstrainedMap& map, const Eigen::Vector3d& p_W);

/// The kind of a swing leg's contact with the contralateral leg: crossing when the swing foot is on
/// the far side of the contralateral foot from its own side of the body (US 2020/0324412 [0062]), a
/// strike otherwise.
ImpactKind ClassifyContralateral(const Eigen::Vector3d& swing_foot_W, const Eigen::Vector3d& contralateral_foot_W,
                                 bool swing_leg_left, double body_yaw);

}  // namespace stairplan
