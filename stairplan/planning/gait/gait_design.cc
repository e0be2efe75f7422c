#include "stairplan/planning/gait/gait_design.h"

#include <cmath>
#include <limits>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void RequirePositive(const char* field, double v) {
  if (!std::isfinite(v) || v <= 0.0) {
    throw FieldError(field, "must be a finite number > 0 (got " + std::to_string(v) + ")");
  }
}

GaitCondition Condition(const char* name, const char* text, double slack, bool strict) {
  GaitCondition c;
  c.name = name;
  c.text = text;
  c.slack = slack;
  c.holds = std::isfinite(slack) && (strict ? slack > 0.0 : slack >= -1e-12);
  return c;
}

}  // namespace

void GaitDesignInput::Validate() const {
  RequirePositive("rise", rise);
  RequirePositive("run", run);
  RequirePositive("max_leg_length", max_leg_length);
  RequirePositive("body_length", body_length);
  RequirePositive("body_width", body_width);
  if (!std::isfinite(buffer) || buffer < 0.0 || buffer >= 1.0) {
    throw FieldError("buffer", "must be in [0, 1) (got " + std::to_string(buffer) + ")");
  }
  if (hip_clearance && (!std::isfinite(*hip_clearance) || *hip_clearance < 0.0)) {
    throw FieldError("hip_clearance", "must be a finite number >= 0 (got " + std::to_string(*hip_clearance) + ")");
  }
}

double MinLegLength(double run, double rise) { return (run * run + rise * rise) / (2.0 * run); }

double ContactOffset(double leg_length, double hip_clearance, double run, double rise) {
  const double cl = std::hypot(run, rise);
  const double arm2 = leg_length * leg_length - 0.25 * cl * cl;
  if (arm2 < 0.0) return kNaN;
  const double sin_phi = rise / cl;
  return (std::sqrt(arm2) - hip_clearance) / sin_phi;
}

double SwingStartSeparation(double max_leg_length, double run, double rise) {
  const double cl = std::hypot(run, rise);
  const double arm2 = max_leg_length * max_leg_length - 0.25 * cl * cl;
  if (arm2 < 0.0) return kNaN;
  return run / rise * std::sqrt(arm2) - 0.5 * cl;
}

double Remainder(double x, double y) {
  const double r = std::fmod(x, y);
  return r < 0.0 ? r + y : r;
}

GaitDesign DesignGait(const GaitDesignInput& input) {
  input.Validate();
  const double W = input.run;
  const double H = input.rise;
  GaitDesign g;
  g.cl = std::hypot(W, H);
  g.phi = std::atan2(H, W);
  g.l_min = MinLegLength(W, H);
  g.d = input.HipClearance();
  // At l = l_min eq. (3) reduces to eq. (4): a = l_min - d csc(phi).
  g.a_min = g.l_min - g.d / std::sin(g.phi);
  g.a_max = ContactOffset(input.max_leg_length, g.d, W, H);
  g.d_s = SwingStartSeparation(input.max_leg_length, W, H);
  g.d_i = (1.0 - input.buffer) * g.d_s;
  g.d_o = (2.0 - input.buffer) * g.d_s;
  g.rem = Remainder(input.body_length, g.cl);
  // (8) and (9) hold for any BL once BL is reduced modulo CL: the front pair's swing window starts
  // rem(BL, CL) before the hind pair's on a circle of length CL, and the two may not overlap.
  // Without (10) there is no positive D_o, so (8) and (9) are void (NaN slack, not holding).
  const bool has_window = g.d_s > 0.0;
  g.conditions[0] = Condition("(10)", "l_max > l_min", input.max_leg_length - g.l_min, true);
  g.conditions[1] = Condition("(8)", "rem(BL, CL) + D_o <= CL", has_window ? g.cl - g.rem - g.d_o : kNaN, false);
  g.conditions[2] = Condition("(9)", "rem(BL, CL) >= D_o", has_window ? g.rem - g.d_o : kNaN, false);
  g.conditions[3] = Condition("(4)", "a_min >= 0 (the right feet land on the tread)", g.a_min, false);
  g.conditions[4] = Condition("(3)", "a_max <= W (the left feet land on the tread)", W - g.a_max, false);
  g.feasible = true;
  for (const GaitCondition& c : g.conditions) {
    if (!c.holds) {
      g.feasible = false;
      g.binding = c.name;
      break;
    }
  }
  if (g.feasible) {
    double tightest = std::numeric_limits<double>::infinity();
    for (const GaitCondition& c : g.conditions) {
      if (c.slack < tightest) {
        tightest = c.slack;
        g.binding = c.name;
      }
    }
  }
  return g;
}

}  // namespace stairplan
