// The legs' names as the robots' models give them: side (L, R), then end (F, H).
#pragma once

#include <string>

namespace stairplan::testing {

/// The leg at the other end of the body on the same side: LF <-> LH, RF <-> RH.
inline std::string SameSideLeg(const std::string& leg) { return std::string(1, leg[0]) + (leg[1] == 'F' ? "H" : "F"); }

}  // namespace stairplan::testing
