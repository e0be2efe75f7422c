// Gaits of the fixed-cadence controllers: which legs swing together and in which order. Legs are
// named by where they are relative to the direction of travel (rear/fore, right/left), so the same
// pattern serves a robot facing forward or backward.
#pragma once

#include <array>

#include "stairplan/planning/plan_gait.h"

namespace stairplan {

/// A leg's place relative to travel.
enum class TravelRole { kRearRight = 0, kRearLeft = 1, kForeRight = 2, kForeLeft = 3 };

/// The phases of one gait cycle; each phase swings `legs_per_phase` legs (given as roles).
struct GaitPattern {
  int phases = 4;  ///< phases per cycle
  int legs_per_phase = 1;  ///< legs swinging together in a phase
  /// The roles swinging in each phase (the first legs_per_phase entries).
  std::array<std::array<TravelRole, 2>, 4> phase_roles{};

  /// Swing legs per cycle: phases * legs_per_phase (always 4).
  int legs_per_cycle() const { return phases * legs_per_phase; }
  /// Stance time of a leg per cycle, in swing durations (crawl 3, trot 1).
  double stance_in_swings() const { return static_cast<double>(phases - 1); }
};

/// The pattern of a controller's `gait`; throws std::invalid_argument for the paper's crawls, which
/// no controller walks (StepPlannerSettings::Validate refuses them).
const GaitPattern& PatternOf(Gait gait);

}  // namespace stairplan
