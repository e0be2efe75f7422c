#include "stairplan/simulation/sim_settings.h"

#include <cmath>
#include <map>
#include <string>

#include "stairplan/geometry/field_error.h"

namespace stairplan {

void SimSettings::Validate() const {
  world.Validate();
  swing.Validate();
  ik.Validate();
  const auto check = [](const char* name, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi) throw FieldError(name, "out of range (got " + std::to_string(v) + ")");
  };
  check("kp_per_kg", kp_per_kg, 0.0, 1e4);
  check("kd_per_kg", kd_per_kg, 0.0, 1e3);
  check("xy_kp", xy_kp, 0.0, 1e5);
  check("xy_kd", xy_kd, 0.0, 1e4);
  check("height_kp", height_kp, 0.0, 1e5);
  check("height_kd", height_kd, 0.0, 1e4);
  check("attitude_kp", attitude_kp, 0.0, 1e5);
  check("attitude_kd", attitude_kd, 0.0, 1e4);
  stance.Validate();
  check("acceleration_feedforward", acceleration_feedforward, 0.0, 2.0);
  check("swing_inertia_feedforward", swing_inertia_feedforward, 0.0, 2.0);
  check("stance_pd_scale", stance_pd_scale, 0.0, 1.0);
  check("load_ramp_time", load_ramp_time, 0.0, 1.0);
  check("swing_pose_feedback", swing_pose_feedback, 0.0, 1.0);
  check("time_scale", time_scale, 0.1, 100.0);
  check("settle_time", settle_time, 0.0, 10.0);
  check("hold_time", hold_time, 0.0, 10.0);
  check("touchdown_phase", touchdown_phase, 0.0, 1.0);
  check("late_descent_speed", late_descent_speed, 0.0, 10.0);
  check("late_descent_max", late_descent_max, 0.0, 1.0);
  check("fall_angle", fall_angle, 0.01, 3.2);
  check("goal_tolerance", goal_tolerance, 1e-4, 10.0);
  check("frame_interval", frame_interval, 0.0, 100.0);
  impact.Validate();
  try {
    mpc.Validate();
  } catch (const FieldError& e) {
    throw FieldError("mpc." + e.field(), e.problem());  // as Set() spells it
  }
  check("mpc_period", mpc_period, 1e-3, 0.1);
}

void SimSettings::Set(const std::string& name, double value) {
  const std::map<std::string, double*> fields = {
      {"world.friction", &world.friction}, {"world.timestep", &world.timestep},
      {"world.default_damping", &world.default_damping}, {"world.armature", &world.armature},
      {"world.effort_scale", &world.effort_scale},
      {"world.detect_margin", &world.detect_margin}, {"world.impratio", &world.impratio},
      {"kp_per_kg", &kp_per_kg}, {"kd_per_kg", &kd_per_kg}, {"xy_kp", &xy_kp}, {"xy_kd", &xy_kd},
      {"height_kp", &height_kp}, {"height_kd", &height_kd}, {"attitude_kp", &attitude_kp},
      {"attitude_kd", &attitude_kd}, {"swing_pose_feedback", &swing_pose_feedback}, {"settle_time", &settle_time}, {"time_scale", &time_scale},
      {"hold_time", &hold_time}, {"touchdown_phase", &touchdown_phase}, {"late_descent_speed", &late_descent_speed},
      {"late_descent_max", &late_descent_max}, {"fall_angle", &fall_angle}, {"goal_tolerance", &goal_tolerance},
      {"frame_interval", &frame_interval}, {"acceleration_feedforward", &acceleration_feedforward},
      {"stance_pd_scale", &stance_pd_scale}, {"swing_inertia_feedforward", &swing_inertia_feedforward}, {"load_ramp_time", &load_ramp_time},
      {"stance.friction_use", &stance.friction_use}, {"stance.torque_use", &stance.torque_use},
      {"stance.min_normal", &stance.min_normal},
      {"stance.force_weight", &stance.force_weight}, {"stance.moment_weight", &stance.moment_weight},
      {"stance.regularization", &stance.regularization},
      {"impact.force_threshold", &impact.force_threshold}, {"impact.min_reswing_time", &impact.min_reswing_time},
      {"impact.retract_distance", &impact.retract_distance}, {"impact.hop_time", &impact.hop_time},
      {"impact.elevate_height", &impact.response.elevate_height},
      {"impact.early_swing_phase", &impact.response.early_swing_phase},
      {"mpc.knot_dt", &mpc.knot_dt}, {"mpc.friction_use", &mpc.friction_use}, {"mpc.min_normal", &mpc.min_normal},
      {"mpc.attitude_weight", &mpc.attitude_weight}, {"mpc.position_weight", &mpc.position_weight},
      {"mpc.angular_velocity_weight", &mpc.angular_velocity_weight}, {"mpc.velocity_weight", &mpc.velocity_weight},
      {"mpc.force_weight", &mpc.force_weight}, {"mpc_period", &mpc_period}};
  if (name == "mpc.knots") {
    if (!(value >= 2.0 && value <= 50.0) || value != std::floor(value)) throw FieldError(name, "must be an integer in [2, 50]");
    mpc.knots = static_cast<int>(value);
    return;
  }
  const auto it = fields.find(name);
  if (it == fields.end()) throw FieldError(name, "no such simulation setting");
  *it->second = value;
}

}  // namespace stairplan
