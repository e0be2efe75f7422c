// Responses to impacts while traversing stairs (US 2020/0324412 A1 ("Robotically negotiating
// stairs") [0053]-[0068], claims 5-8): given what hit what and where the swing leg is in its swing,
// decide how the robot reacts. Pure decision logic; the impact detector that produces the events
// lives with the controller or the simulator.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/constrained_map.h"

namespace stairplan {

/// What was detected (paragraphs of US 2020/0324412 A1, "Robotically negotiating stairs").
enum class ImpactKind {
  kTouchdown,              ///< the swing foot reached its target tread ([0055])
  kKneeBehindBody,         ///< a trailing knee hit something behind the body ([0058])
  kContralateralStrike,    ///< the swing leg struck the contralateral stance leg, not crossing ([0063])
  kContralateralCrossing,  ///< ... and crossed over it ([0062])
  kTrip,                   ///< the swing leg hit an obstacle it must swing over ([0064])
  kThighAgainstBody,       ///< the thigh touched the body ([0066])
  kLiftoffScuff,           ///< the foot scuffed the tread at liftoff ([0067])
  kKneeGlancingTerrain,    ///< the knee glanced a tread or nosing while swinging ([0068])
  kIpsilateralStrike,      ///< the swing foot struck the other leg of its own side ([0053]: front and hind legs)
  /// The swing foot came down outside every step region (on a nosing, against a riser): not the
  /// touchdown of [0055], which is in the target step location; the step moves into the region ([0060]).
  kMisplacedTouchdown,
};

/// How to react.
enum class ResponseKind {
  kClassifyStance,        ///< the swing leg becomes a stance leg
  kMoveKneeForward,       ///< move the knee forward, beneath the body
  kAdjustStep,            ///< new target inside the step region, away from the contralateral leg
  kAdjustStepRisky,       ///< no free step region: the least risky spot of a collision region
  kUntangle,              ///< fore/aft first, then sideways (waypoints), then the adjusted target
  kElevateFoot,           ///< raise the swing foot higher (early in swing)
  kTouchdownNow,          ///< put the foot down at once (late in swing)
  kProceed,               ///< no reaction: continue the planned motion
};

/// Returns the kind's snake_case name, e.g. "knee_behind_body".
const char* ToString(ImpactKind kind);
/// Returns the response's snake_case name, e.g. "move_knee_forward".
const char* ToString(ResponseKind kind);

/// One detected impact with the state the response needs. Positions in the world frame [m].
struct ImpactEvent {
  ImpactKind kind = ImpactKind::kTouchdown;  ///< what was detected
  std::string leg;                 ///< the swing (or impacted) leg: "LF", "RF", "LH", "RH"
  double swing_phase = 0.0;        ///< 0 at liftoff, 1 at planned touchdown
  double body_yaw = 0.0;           ///< body heading, to know which way is the leg's own side [rad]
  int target_stair = -1;           ///< the stair the swing foot is heading for
  Eigen::Vector3d swing_foot_W = Eigen::Vector3d::Zero();  ///< the swing foot now
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< where the swing foot is heading
  Eigen::Vector3d contralateral_foot_W = Eigen::Vector3d::Zero();  ///< the contralateral leg's foot
};

/// Tunable parts of the responses, with defaults for a medium quadruped.
struct ImpactSettings {
  double early_swing_phase = 0.5;        ///< below this phase a trip elevates, above it touches down
  double elevate_height = 0.06;          ///< extra swing height after an early trip [m]
  double contralateral_clearance = 0.10; ///< lateral gap kept from the contralateral foot [m]
  double untangle_distance = 0.06;       ///< fore/aft move before sideways when legs crossed [m]
  double knee_forward_distance = 0.05;   ///< how far the knee moves forward [m]
  double step_region_margin = 0.01;      ///< how far inside the step region a moved foot aims [m]

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The reaction to one impact.
struct ImpactResponse {
  ResponseKind kind = ResponseKind::kProceed;  ///< the reaction
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< the (possibly adjusted) foot target
  std::vector<Eigen::Vector3d> waypoints_W;            ///< intermediate foot positions, in order
  double extra_swing_height = 0.0;                     ///< for kElevateFoot [m]
  double knee_forward = 0.0;                           ///< for kMoveKneeForward [m]
  std::string reason;                                  ///< one line for logs and tests
};

/// Decides the response to `event` on `map`. Never throws for geometry it cannot handle.
ImpactResponse RespondToImpact(const ImpactEvent& event, const ConstrainedMap& map, const ImpactSettings& settings = {});

}  // namespace stairplan
