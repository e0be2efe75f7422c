#include "planning/plan.h"

namespace stairplan {

const char* ToString(PlanStatus status) { return status == PlanStatus::kOk ? "ok" : "infeasible"; }

}  // namespace stairplan
