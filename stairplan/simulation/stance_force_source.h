// Where the executor's stance forces come from: one enum for the settings, the outcome and the CLI.
#pragma once

#include <string>

namespace stairplan {

/// Where the executor's stance forces come from.
enum class StanceForceSource {
  /// The convex MPC for a gait that stands on two feet (the trot: not IsQuasiStatic), where no
  /// instantaneous distribution can hold the body's attitude; the wrench for the others, whose
  /// three or four feet can (and which it executes more gently).
  kByGait,
  kWrench,     ///< the PD wrench of the planned body, distributed over the stance feet each step
  kConvexMpc,  ///< the convex MPC's first knot (stairplan/simulation/convex_mpc.h)
};

/// "gait", "wrench" or "mpc".
const char* ToString(StanceForceSource source);
/// The source ToString() names `text`; throws FieldError("stance_forces") otherwise.
StanceForceSource ParseStanceForceSource(const std::string& text);

}  // namespace stairplan
