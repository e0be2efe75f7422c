#include "stairplan/sweep/pipeline_sweep_row.h"

namespace stairplan {

SweepRow PipelineSweepRow(const SweepPoint& point, const PipelineResult& result) {
  SweepRow row;
  row.point = point;
  row.cadence_s = result.plan.cadence_s;
  row.footsteps = static_cast<int>(result.plan.footsteps.size());
  row.gait = result.plan.gait;
  for (const auto& [stage, us] : result.plan.timing_us) (stage == "validate" ? row.validate_us : row.plan_us) += us;
  if (result.plan.status != PlanStatus::kOk) {
    row.status = "infeasible";
    row.reason = result.plan.status_reason;
    return row;
  }
  if (!result.validated) {
    row.status = "planned";
    return row;
  }
  const ValidationReport& v = result.validation;
  row.min_clearance_m = v.min_clearance_m;
  row.min_stability_margin_m = v.min_stability_margin_m;
  row.status = v.ok ? "valid" : "invalid";
  if (!v.violations.empty()) {
    const Violation& first = v.violations.front();
    row.reason = std::string(ToString(first.kind)) + " " + first.leg + (first.detail.empty() ? "" : " " + first.detail);
  }
  return row;
}

}  // namespace stairplan
