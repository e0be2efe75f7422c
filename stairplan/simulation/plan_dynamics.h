// Whether a plan's body motion can be carried by its feet at the pace it is executed: the
// zero-moment point of the cart-table model (centre of mass minus its horizontal acceleration
// times height over g) against the support polygon of the feet the plan has down. Contact forces
// can only push, so their centre of pressure lies inside that polygon; a plan whose ZMP leaves it
// asks for a moment no stance can give, and the body tips whatever the controller does. Playing
// the plan s times slower divides the accelerations by s^2: this is what a slowed replay hides.
#pragma once

#include <limits>

#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// The worst instant of a plan's ZMP against its support polygon.
struct ZmpMargin {
  /// Smallest signed distance of the ZMP inside the support polygon [m]; negative: outside.
  double margin_m = 0.0;
  double t = 0.0;                  ///< when [s, plan time]
  double max_acceleration = 0.0;   ///< largest horizontal body acceleration at this pace [m/s^2]
};

/// The ZMP margin of `plan` for `robot` played `time_scale` times slower than planned, sampled
/// every `dt` of plan time, with the body's acceleration from the executor's reference (the
/// cubic spline through the body samples), up to plan time `until` (the whole plan by default).
/// Instants with fewer than three feet down are skipped.
ZmpMargin PlanZmpMargin(const RobotModel& robot, const Plan& plan, double time_scale, double dt = 0.005,
                        double until = std::numeric_limits<double>::infinity());

}  // namespace stairplan
