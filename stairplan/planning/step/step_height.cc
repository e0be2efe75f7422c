#include "stairplan/planning/step/step_height.h"

#include <cmath>
#include <cstdio>

namespace stairplan {

double MaxStepHeight(const LegModel& leg, const StepPlannerSettings& settings) {
  return settings.max_step_height_fraction * leg.max_reach;
}

std::optional<RiseTooHigh> FirstRiseTooHigh(const std::vector<LegModel>& legs, const ConstrainedMap& map,
                                            const StepPlannerSettings& settings) {
  const LegModel* lowest = nullptr;
  for (const LegModel& leg : legs) {
    if (lowest == nullptr || MaxStepHeight(leg, settings) < MaxStepHeight(*lowest, settings)) lowest = &leg;
  }
  if (lowest == nullptr) return std::nullopt;
  const double max_step = MaxStepHeight(*lowest, settings);
  for (int k = 1; k < map.size(); ++k) {
    const double rise = std::abs(map.stair(k).z - map.stair(k - 1).z);
    if (rise > max_step) {
      return RiseTooHigh{k, rise, lowest->name, max_step, lowest->max_reach, settings.max_step_height_fraction};
    }
  }
  return std::nullopt;
}

std::string ToString(const RiseTooHigh& r) {
  char text[256];
  std::snprintf(text, sizeof text,
                "step height: the rise onto surface %d is %.3f m, higher than %s can step (%.3f m: "
                "max_step_height_fraction %.2f of its %.3f m reach)",
                r.surface, r.rise, r.leg.c_str(), r.max_step, r.fraction, r.max_reach);
  return text;
}

}  // namespace stairplan
