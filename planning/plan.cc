#include "planning/plan.h"

namespace stairplan {

const char* ToString(PlanStatus status) { return status == PlanStatus::kOk ? "ok" : "infeasible"; }

const char* ToString(BodyPlannerKind kind) {
  switch (kind) {
    case BodyPlannerKind::kQuasiStaticPath: return "quasi_static_path";
    case BodyPlannerKind::kRecedingHorizonQp: return "receding_horizon_qp";
    case BodyPlannerKind::kRecedingHorizonNlp: return "receding_horizon_nlp";
  }
  return "unknown";
}

const char* ToString(BodyPlanStatus status) {
  switch (status) {
    case BodyPlanStatus::kOk: return "ok";
    case BodyPlanStatus::kStale: return "stale";
    case BodyPlanStatus::kInfeasible: return "infeasible";
  }
  return "unknown";
}

}  // namespace stairplan
