#include "stairplan/planning/validation/leg_id.h"

namespace stairplan {

const char* ToString(LegId leg) {
  switch (leg) {
    case LegId::kLeftFront: return "LF";
    case LegId::kRightFront: return "RF";
    case LegId::kLeftHind: return "LH";
    case LegId::kRightHind: return "RH";
    case LegId::kNone: return "none";
  }
  return "none";
}

LegId LegIdFromIndex(int index) {
  return index >= 0 && index < 4 ? static_cast<LegId>(index) : LegId::kNone;
}

}  // namespace stairplan
