// The JSON form of a physics run's outcome (what `stairplan simulate` prints).
#pragma once

#include <nlohmann/json.hpp>

#include "planning/simulation/sim_outcome.h"

namespace stairplan {

/// Everything in the outcome except the recorded frames.
nlohmann::json SimulationToJson(const SimulationOutcome& outcome);

}  // namespace stairplan
