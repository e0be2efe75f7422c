#include "stairplan/planning/plan.h"

#include <algorithm>

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

RelaxedCycles SummariseRelaxed(const std::vector<BodyCycleStats>& cycles) {
  RelaxedCycles summary;
  for (const BodyCycleStats& c : cycles) {
    if (!c.relaxed()) continue;
    if (summary.count++ == 0) summary.first_t = c.t;
    summary.most = std::max(summary.most, c.relaxation);
  }
  return summary;
}

}  // namespace stairplan
