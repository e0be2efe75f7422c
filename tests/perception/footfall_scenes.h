// The footfall loop of seed 001 [0047]: up two flights and down two, each of its own geometry.
#pragma once

#include <vector>

#include "stairplan/perception/footfall_walk.h"

namespace stairplan::testing {

/// Four flights: up 6 x (0.17, 0.28) heading +x, up 5 x (0.15, 0.30) heading +y, down
/// 6 x (0.16, 0.26) heading -x, down 5 x (0.162, 0.29) heading -y, back near the start.
std::vector<PlacedFlight> TwoUpTwoDownLoop();

}  // namespace stairplan::testing
