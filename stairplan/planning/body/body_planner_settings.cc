#include "stairplan/planning/body/body_planner_settings.h"

#include <cmath>
#include <map>
#include <string>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

void CheckRange(const char* field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value <= lo || value > hi) {
    throw FieldError(field, "must be in (" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                                std::to_string(value) + ")");
  }
}

}  // namespace

void BodyPlannerSettings::Validate() const {
  if (knots < 3 || knots > 400) throw FieldError("knots", "must be in [3, 400] (got " + std::to_string(knots) + ")");
  CheckRange("knot_dt", knot_dt, 0.0, 1.0);
  CheckRange("hip_height_fraction", hip_height_fraction, 0.0, 1.0);
  CheckRange("stairs_com_shift", stairs_com_shift, -1.0, 1.0);
  CheckRange("height_weight", height_weight, 0.0, 1e9);
  CheckRange("pitch_weight", pitch_weight, 0.0, 1e9);
  CheckRange("shift_weight", shift_weight, 0.0, 1e9);
  CheckRange("velocity_weight", velocity_weight, 0.0, 1e9);
  CheckRange("acceleration_weight", acceleration_weight, 0.0, 1e9);
  CheckRange("max_pitch", max_pitch, 0.0, 1.5);
  CheckRange("max_shift", max_shift, 0.0, 1.0);
  if (std::abs(stairs_com_shift) > max_shift) throw FieldError("stairs_com_shift", "must be within max_shift");
  CheckRange("max_height_accel", max_height_accel, 0.0, 1e3);
  CheckRange("max_pitch_accel", max_pitch_accel, 0.0, 1e4);
  CheckRange("max_shift_accel", max_shift_accel, 0.0, 1e3);
  if (!std::isfinite(stability_margin) || stability_margin > 0.2) throw FieldError("stability_margin", "must be finite and at most 0.2 m");
  CheckRange("min_stability_margin", min_stability_margin, 0.0, 0.2);
  CheckRange("checked_stability_margin", checked_stability_margin, 0.0, 0.2);
  CheckRange("max_retreat", max_retreat, 0.0, 10.0);
  CheckRange("lateral_weight", lateral_weight, 0.0, 1e9);
  CheckRange("max_lateral_shift", max_lateral_shift, 0.0, 1.0);
  CheckRange("max_lateral_accel", max_lateral_accel, 0.0, 1e3);
  CheckRange("trust_lateral", trust_lateral, 0.0, 1.0);
  if (!(relinearise_share >= 0.0 && relinearise_share <= 1.0)) throw FieldError("relinearise_share", "must be in [0, 1]");
  if (!(reach_margin >= 0.0 && reach_margin <= 0.5)) throw FieldError("reach_margin", "must be in [0, 0.5] m");
  if (!(joint_margin >= 0.0 && joint_margin <= 0.5)) throw FieldError("joint_margin", "must be in [0, 0.5] rad");
  if (!(clearance_margin >= 0.0 && clearance_margin <= 0.5)) throw FieldError("clearance_margin", "must be in [0, 0.5] m");
  CheckRange("grid_dx", grid_dx, 0.0, 0.5);
  CheckRange("grid_pitch", grid_pitch, 0.0, 1.0);
  CheckRange("grid_height", grid_height, 0.0, 0.2);
  CheckRange("trust_pitch", trust_pitch, 0.0, 1.0);
  CheckRange("trust_shift", trust_shift, 0.0, 1.0);
  CheckRange("cycle_budget_s", cycle_budget_s, 0.0, 10.0);
  if (warmup_solves < 1 || warmup_solves > 100000) throw FieldError("warmup_solves", "must be in [1, 100000]");
}

void BodyPlannerSettings::Set(const std::string& name, double value) {
  if (name == "knots") {
    if (!(value >= 3 && value <= 400 && value == std::floor(value))) throw FieldError(name, "must be a whole number in [3, 400]");
    knots = static_cast<int>(value);
    return;
  }
  if (name == "stance_rows") {
    if (!(value == 0.0 || value == 1.0)) throw FieldError(name, "must be 0 (off) or 1 (on)");
    stance_rows = value == 1.0;
    return;
  }
  if (name == "warmup_solves") {
    if (!(value >= 1 && value <= 100000 && value == std::floor(value))) throw FieldError(name, "must be a whole number in [1, 100000]");
    warmup_solves = static_cast<int>(value);
    return;
  }
  const std::map<std::string, double*> fields = {
      {"knot_dt", &knot_dt}, {"hip_height_fraction", &hip_height_fraction}, {"stairs_com_shift", &stairs_com_shift},
      {"height_weight", &height_weight}, {"pitch_weight", &pitch_weight}, {"shift_weight", &shift_weight},
      {"velocity_weight", &velocity_weight}, {"acceleration_weight", &acceleration_weight}, {"max_pitch", &max_pitch},
      {"max_shift", &max_shift}, {"max_height_accel", &max_height_accel}, {"max_pitch_accel", &max_pitch_accel},
      {"max_shift_accel", &max_shift_accel}, {"stability_margin", &stability_margin},
      {"min_stability_margin", &min_stability_margin}, {"checked_stability_margin", &checked_stability_margin},
      {"max_retreat", &max_retreat},
      {"lateral_weight", &lateral_weight},
      {"max_lateral_shift", &max_lateral_shift}, {"max_lateral_accel", &max_lateral_accel}, {"reach_margin", &reach_margin},
      {"joint_margin", &joint_margin},
      {"clearance_margin", &clearance_margin}, {"grid_dx", &grid_dx}, {"grid_pitch", &grid_pitch},
      {"grid_height", &grid_height}, {"trust_pitch", &trust_pitch}, {"trust_shift", &trust_shift},
      {"trust_lateral", &trust_lateral}, {"relinearise_share", &relinearise_share},
      {"cycle_budget_s", &cycle_budget_s}};
  const auto it = fields.find(name);
  if (it == fields.end()) throw FieldError(name, "no such body planner setting");
  *it->second = value;
}

BodyPlannerSettings LegRowBodySettings() {
  BodyPlannerSettings s;
  s.stance_rows = true;
  // Executed, the body tracks its plan to about a degree of pitch: in MuJoCo the built-in robot's
  // shanks pass the stairs 5-6 mm nearer than planned (1.8 mm left of the 6 mm its rows keep at
  // no margin, 5.5 mm of 11 mm at 5 mm), so the plan keeps the validator's 5 mm plus that much.
  s.clearance_margin = 0.005;
  s.stability_margin = 0.03;
  s.hip_height_fraction = 0.6;
  s.max_shift = 0.15;
  s.max_lateral_shift = 0.15;
  // Sideways no faster than fore-aft: the crawl crosses the body 13 cm sideways between support
  // triangles, and at 6 m/s^2 the pendulum's ZMP of Go2's crossing lay 0.19 m outside its support
  // (it fell in MuJoCo, up and down); at the fore-aft bound it walks both.
  s.max_lateral_accel = s.max_shift_accel;
  s.acceleration_weight = 1.0;
  s.knots = 20;
  s.knot_dt = 0.05;
  s.trust_shift *= 2.0;
  s.trust_lateral *= 2.0;
  s.trust_pitch *= 2.0;
  return s;
}

}  // namespace stairplan
