// The JSON form of a physics run's outcome (what `stairplan simulate` prints).
#pragma once

#include <nlohmann/json.hpp>

#include "stairplan/simulation/sim_outcome.h"

namespace stairplan {

/// Everything in the outcome except the recorded frames.
nlohmann::json SimulationToJson(const SimulationOutcome& outcome);
/// The recorded frames (for `stairplan view --sim`): [{t, base, roll_pitch_yaw, q {leg: [3 angles]}}].
nlohmann::json SimFramesToJson(const std::vector<SimFrame>& frames);

}  // namespace stairplan
