// Settings of a physics run: the simulated world, the executor's controller (joint PD with gravity
// compensation, stance forces from a QP over the stance feet), touchdown handling, and what counts as a
// fall, a stall or a success.
#pragma once

#include <string>

#include "stairplan/kinematics/leg_ik.h"
#include "stairplan/simulation/convex_mpc.h"
#include "stairplan/simulation/impact_detection.h"
#include "stairplan/simulation/mjcf_writer.h"
#include "stairplan/simulation/stance_force_qp.h"
#include "stairplan/simulation/stance_force_source.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

/// The simulated world, the controller, impact detection and judging of a MuJoCo run.
struct SimSettings {
  /// Contact and integration (friction kStairFriction, 1 kHz), with links reported within 1 cm of the stairs
  /// so that clearances can be compared with the validator's margin.
  MjcfSettings world = [] {
    MjcfSettings w;
    w.detect_margin = 0.01;
    return w;
  }();
  SwingSettings swing;               ///< for footsteps whose plan gives no swing apex
  IkSettings ik;  ///< IK of the foot targets

  // Controller. Gains scale with the robot's mass so that one setting suits a 12 kg Unitree and a
  // 50 kg ANYmal alike.
  double kp_per_kg = 8.0;            ///< joint stiffness per kg of robot [N m/rad/kg]
  double kd_per_kg = 0.2;            ///< joint damping per kg of robot [N m s/rad/kg]
  double xy_kp = 400.0;              ///< base position feedback along the ground [1/s^2] (times mass)
  double xy_kd = 40.0;               ///< [1/s]
  double height_kp = 800.0;          ///< base height feedback [1/s^2] (times mass)
  double height_kd = 60.0;           ///< [1/s]
  double attitude_kp = 300.0;        ///< base attitude feedback [1/s^2] (times the robot's inertia about its COM)
  double attitude_kd = 30.0;         ///< [1/s]
  /// Share of the plan's body acceleration the stance forces feed forward (1: all of it).
  double acceleration_feedforward = 1.0;
  /// Share of a swinging leg's inertia times its target acceleration added to its torques.
  double swing_inertia_feedforward = 1.0;
  /// A loaded stance leg keeps this share of its joint PD; its contact force does the carrying.
  double stance_pd_scale = 0.3;
  /// A foot takes its load over this time after touchdown and gives it up over this time before
  /// its liftoff [s].
  double load_ramp_time = 0.05;
  /// How the stance forces are distributed (friction: the world's).
  StanceForceSettings stance;
  /// Where the stance forces come from: the convex MPC over the plan's next knots, or the
  /// instantaneous distribution of the PD wrench (StanceForceQp).
  StanceForceSource stance_forces = StanceForceSource::kByGait;
  /// The convex MPC's horizon and weights (friction: the world's), wherever stance_forces picks it.
  ConvexMpcSettings mpc;
  /// Simulated time between the convex MPC's solves [s]; its first knot's forces hold between.
  double mpc_period = 0.01;
  /// Share of the body-pose error (measured - planned) a swing leg follows so that it lands where
  /// the plan says in the world even when the body lags: 1 = fully, 0 = not at all.
  double swing_pose_feedback = 1.0;

  // Timing and touchdown.
  /// Plays the plan this many times slower (1: as planned). A plan is executed at its own pace;
  /// slowing it divides its accelerations by the square and hides plans that are dynamically
  /// infeasible (every outcome reports the plan's ZMP margin at the pace it was played).
  double time_scale = 1.0;
  double settle_time = 0.5;          ///< standing on the initial footholds before the plan starts [s]
  double hold_time = 1.0;            ///< standing after the plan ends before judging [s]
  double touchdown_phase = 0.5;      ///< a foot contact counts as touchdown from this swing phase on
  double late_descent_speed = 0.2;   ///< a foot late for touchdown keeps lowering at this speed [m/s]
  double late_descent_max = 0.10;    ///< ... by at most this much [m]

  /// Impact detection and the responses to impacts (US 2020/0324412 [0053]-[0068]).
  ImpactDetectionSettings impact;

  // Judgement.
  double fall_angle = 0.6;           ///< roll, or pitch away from the plan's, beyond this is a fall [rad]
  double goal_tolerance = 0.10;      ///< final base position within this of the plan's last pose [m]
  double frame_interval = 0.0;       ///< record a state for the drawings every this [s]; 0: none

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
  /// Sets the numeric field `name` (as spelled above, "world.friction" for the world's) to `value`;
  /// throws std::invalid_argument naming an unknown field.
  void Set(const std::string& name, double value);
};

}  // namespace stairplan
