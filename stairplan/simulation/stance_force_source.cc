#include "stairplan/simulation/stance_force_source.h"

#include "stairplan/geometry/field_error.h"

namespace stairplan {

const char* ToString(StanceForceSource source) {
  switch (source) {
    case StanceForceSource::kByGait: return "gait";
    case StanceForceSource::kWrench: return "wrench";
    case StanceForceSource::kConvexMpc: return "mpc";
  }
  return "unknown";
}

StanceForceSource ParseStanceForceSource(const std::string& text) {
  for (const StanceForceSource s : {StanceForceSource::kByGait, StanceForceSource::kWrench, StanceForceSource::kConvexMpc}) {
    if (text == ToString(s)) return s;
  }
  throw FieldError("stance_forces", "must be 'gait', 'wrench' or 'mpc' (got '" + text + "')");
}

}  // namespace stairplan
