#include "stairplan/planning/step/step_planner_settings.h"

#include <cmath>
#include <string>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

void Check(const std::string& name, double v, double lo, double hi, bool lo_open = true) {
  const bool low_ok = lo_open ? v > lo : v >= lo;
  if (!std::isfinite(v) || !low_ok || v > hi) {
    throw FieldError(name, std::string("must be in ") + (lo_open ? "(" : "[") + std::to_string(lo) + ", " +
                               std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  }
}

}  // namespace

void StepPlannerSettings::Validate() const {
  if (cadences_s.empty()) throw FieldError("cadences_s", "needs at least one cadence");
  if (cadences_s.size() > 64) throw FieldError("cadences_s", "at most 64 cadences");
  for (std::size_t i = 0; i < cadences_s.size(); ++i) {
    Check("cadences_s[" + std::to_string(i) + "]", cadences_s[i], 0.0, 5.0);
  }
  if (gaits.empty()) throw FieldError("gaits", "needs at least one gait");
  if (gaits.size() > 8) throw FieldError("gaits", "at most 8 gaits");
  for (const Gait g : gaits) {
    if (g == Gait::kPaperCrawl || g == Gait::kPaperCrawlAlternate) {
      throw FieldError("gaits", std::string(ToString(g)) + " is the paper's crawl, planned by its own footstep planner, not a controller");
    }
  }
  if (horizon_steps < 1 || horizon_steps > 64) {
    throw FieldError("horizon_steps", "must be between 1 and 64 (got " + std::to_string(horizon_steps) + ")");
  }
  Check("hip_height_fraction", hip_height_fraction, 0.0, 1.0);
  Check("max_step_height_fraction", max_step_height_fraction, 0.0, 1.0);
  Check("reach_min_fraction", reach_min_fraction, 0.0, 1.0, false);
  Check("reach_max_fraction", reach_max_fraction, 0.0, 1.0);
  if (reach_min_fraction >= reach_max_fraction) {
    throw FieldError("reach_min_fraction", "must be below reach_max_fraction");
  }
  Check("target_margin", target_margin, 0.0, 0.5, false);
  if (candidate_stairs < 0 || candidate_stairs > 8) {
    throw FieldError("candidate_stairs", "must be between 0 and 8 (got " + std::to_string(candidate_stairs) + ")");
  }
  Check("region_weight", region_weight, 0.0, 1e9, false);
  Check("snap_weight", snap_weight, 0.0, 1e9, false);
  Check("trailing_cost", trailing_cost, 0.0, 1e9, false);
  Check("swing_height_weight", swing_height_weight, 0.0, 1e9, false);
  Check("reach_weight", reach_weight, 0.0, 1e9, false);
  Check("timing_weight", timing_weight, 0.0, 1e9, false);
  Check("max_foot_speed", max_foot_speed, 0.0, 100.0);
  Check("switch_cost", switch_cost, 0.0, 1e9, false);
  Check("gait_switch_cost", gait_switch_cost, 0.0, 1e9, false);
  Check("speed", speed, 0.0, 10.0);
  Check("sample_period", sample_period, 0.0, 1.0);
  Check("start_gap", start_gap, -1.0, 5.0);
  Check("settle_s", settle_s, 0.0, 10.0, false);
  if (max_cycles < 1 || max_cycles > 10000000) {
    throw FieldError("max_cycles", "must be between 1 and 10000000 (got " + std::to_string(max_cycles) + ")");
  }
}

}  // namespace stairplan
