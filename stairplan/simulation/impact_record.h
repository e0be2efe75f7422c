// Impacts as the executor met them (US 2020/0324412 A1 ("Robotically negotiating stairs")
// [0053]-[0068]): what hit what, when, how it was found (MuJoCo's contact list or the joint-torque
// residual) and how the robot answered.
#pragma once

#include <string>

#include <Eigen/Core>

#include "stairplan/planning/impact/impact_response.h"

namespace stairplan {

/// Where the executor learns of impacts.
enum class ImpactSource {
  kNone,            ///< no detection: touchdown by foot contact only, no responses
  kContacts,        ///< MuJoCo's contact list: a robot with contact sensors on every link
  kTorqueResidual,  ///< measured minus model-predicted joint torques: a robot without contact sensors
};
/// Returns "none", "contacts" or "torque_residual".
const char* ToString(ImpactSource source);

/// One detected impact and the response carried out.
struct ImpactRecord {
  double t = 0.0;             ///< when it was detected [s, plan time]
  /// When MuJoCo's contact list first showed this leg touching in this swing, the ground truth the
  /// detection latency is measured against; -1 when it showed nothing [s, plan time].
  double t_contact = -1.0;
  double t_planned = -1.0;    ///< touchdowns: the plan's touchdown time (-1 for other kinds) [s, plan time]
  std::string leg;  ///< the leg: "LF", "RF", "LH" or "RH"
  ImpactKind kind = ImpactKind::kTouchdown;  ///< what was detected
  ImpactSource source = ImpactSource::kNone;  ///< what detected it
  ResponseKind response = ResponseKind::kProceed;  ///< the response carried out
  std::string link;           ///< the robot link that was hit (the foot for foot events)
  double swing_phase = 0.0;   ///< 0 at liftoff, 1 at the planned touchdown
  double force_n = 0.0;       ///< the estimated external force at detection [N]
  std::string reason;         ///< the response's one-line reason
  /// Where the hit leg's foot was at detection (for a touchdown: where it landed) [m, world].
  Eigen::Vector3d at_W = Eigen::Vector3d::Zero();
  /// The swing's target after the response: the planned foothold unless the response moved it [m, world].
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();
  /// The response was carried out (false: kProceed, which moves nothing, or recorded only, with
  /// responses off or the leg's quota spent).
  bool executed = false;
};

}  // namespace stairplan
