// Settings of the body planner (US 2020/0324412 A1 ("Robotically negotiating stairs")
// [0050]-[0052]): the horizon, the cost weights, the hard limits, the margins of the kinematic and
// collision bounds, the trust region of the per-cycle linearisation and the cycle budget. Defaults
// suit a medium quadruped on building-code stairs.
#pragma once

#include <string>

#include "stairplan/planning/validity_margins.h"

namespace stairplan {

/// The body planner's settings: horizon, cost weights, hard limits, margins, trust region, budget.
struct BodyPlannerSettings {
  // --- Horizon.
  int knots = 40;             ///< knots over the horizon
  double knot_dt = 0.025;     ///< spacing of the knots [s]

  // --- Targets.
  /// Desired hip height above the feet' contact points (the soft equality of US 2020/0324412
  /// [0052]): the foot radius plus this fraction of the legs' longest hip-to-foot reach within
  /// their joint limits.
  double hip_height_fraction = 0.8;
  /// Forward shift of the centre of mass wanted on the flight (toward the front legs, US
  /// 2020/0324412 [0049]) [m].
  double stairs_com_shift = 0.03;

  // --- Cost weights (per knot).
  double height_weight = 1e4;        ///< per leg, per m^2 of hip-height error
  double pitch_weight = 1e3;         ///< per rad^2 away from the feet's slope
  double shift_weight = 2e3;         ///< per m^2 away from the wanted shift
  double velocity_weight = 1e-1;     ///< per (m/s)^2 and (rad/s)^2 of knot-to-knot change
  double acceleration_weight = 1e-3; ///< per (m/s^2)^2 and (rad/s^2)^2

  // --- Hard limits.
  double max_pitch = 0.8;          ///< |pitch| bound [rad]
  double max_shift = 0.06;         ///< |com_shift| bound [m]
  double max_height_accel = 4.0;   ///< |z''| [m/s^2]
  double max_pitch_accel = 20.0;   ///< |pitch''| [rad/s^2]
  double max_shift_accel = 2.0;    ///< |com_shift''| [m/s^2]

  // --- Static stability (the crawl's quasi-static balance): the centre of mass kept inside the
  // support polygon of the legs that stand through each knot and its neighbours, shifting the
  // weight sideways (com_shift_y) and fore-aft (com_shift) over the support triangle.
  /// How far inside [m]; the validator asks for 1 cm, the rest covers the QP's COM estimate
  /// (com_estimate.h) and the swing legs' own motion. Negative: no stability rows. Off in these
  /// defaults, which have no leg rows to pay the sideways shift's cost in joint range and reach;
  /// LegRowBodySettings() has both.
  double stability_margin = -1.0;
  /// With stance rows, where the polygon leaves no room for stability_margin (a narrow support
  /// triangle against the sideways-shift bound), the support rows give up margin down to this one,
  /// each metre given up costing BodyQp::kMarginGivePenalty [m].
  double min_stability_margin = 0.015;
  /// With stability rows, the exact re-check of the plan (body_check.h) asks the centre of mass,
  /// every leg link placed by IK, to stand this far inside the standing feet's polygon at every
  /// instant: the validator's margin, which the rows' stability_margin plans for with the COM
  /// estimate's error and any relaxed knot to spare [m].
  double checked_stability_margin = kValidStabilityMargin;
  /// With stance rows (which price the body's motion against the travel), the re-check refuses a
  /// plan whose body moves back along the travel farther than this behind where it had been [m].
  double max_retreat = 0.01;
  double lateral_weight = 1e3;     ///< per m^2 of sideways weight shift
  double max_lateral_shift = 0.1;  ///< |com_shift_y| bound [m]
  double max_lateral_accel = 6.0;  ///< |com_shift_y''| [m/s^2]

  // --- Bounds from kinematics and collision.
  double reach_margin = 0.01;      ///< hip height kept this far inside the IK-feasible range [m]
  /// Rows of every stance leg in the QP: its joints within their limits, its extension within
  /// the knee's range and its links clear of the stairs, linearised through KDL and FCL each
  /// cycle (body_qp.h). Off in these defaults (a QP without a robot's legs in it, the fastest
  /// cycle); on in LegRowBodySettings(), the pipeline's body optimisation. Set(): 0 or 1.
  bool stance_rows = false;
  /// Stance legs' joints kept this far inside their limits (the linearised stance rows) [rad].
  double joint_margin = 0.02;
  /// Every stance leg's links at least this far from the stairs [m]. The lower legs of real robots
  /// stand a few millimetres above the tread under the foot, so larger margins rule out standing.
  double clearance_margin = 0.0;
  double grid_dx = 0.03;           ///< spacing of the cached bounds along the heading [m]
  double grid_pitch = 0.1;         ///< spacing of the cached bounds in pitch [rad]
  double grid_height = 0.02;       ///< scan step when searching a feasible hip height [m]

  // --- Linearisation: per cycle, pitch and shift move at most this far from the last plan,
  // and the bounds hold over that whole box (so the linear rows stay conservative).
  double trust_pitch = 0.02;       ///< [rad]
  double trust_shift = 0.004;      ///< [m]
  /// Sideways shift per cycle [m]; the legs' reach is padded for the sideways hip offset it allows.
  double trust_lateral = 0.006;
  /// With stance rows: a knot's leg rows linearised a cycle ago at the same instant are kept
  /// while its centre has moved less than this share of the trust region in every variable
  /// (height: of trust_shift); beyond it, or at 0, they are linearised again (KnotRowCache).
  /// Over the default climbs tried, the plans of 0.25 and 0 differ by at most 1.6 mm.
  double relinearise_share = 0.25;

  // --- Control loop.
  /// Wall-clock budget of one Update [s]; a solve that would overrun returns the shifted
  /// previous plan marked stale.
  double cycle_budget_s = 0.0025;
  /// QP solves at the first Update (and after Reset) to converge the linearisation.
  int warmup_solves = 60;

  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
  /// Sets the field called `name` (as in this struct, e.g. "stability_margin"); throws FieldError
  /// for an unknown name. Call Validate() after the last one.
  void Set(const std::string& name, double value);
};

/// The settings the planning pipeline's body optimisation plans a whole flight with
/// (PipelineOptions::body_qp; `stairplan plan --body qp`): the defaults above with every leg's
/// rows (stance_rows), the support rows 3 cm inside the polygon, hips at 0.6 of the legs' reach,
/// shift boxes of 0.15 m (the leg rows hold the reach, so the boxes only keep out of their way),
/// the sideways shift's acceleration bounded as the fore-aft one's,
/// acceleration priced at 1 (the pendulum turns it into the ZMP's distance from the COM), and a
/// knot every 50 ms over a 1 s horizon, the trust regions doubled with the cycle so the body may
/// move as fast per second as with knots 25 ms apart.
BodyPlannerSettings LegRowBodySettings();

}  // namespace stairplan
