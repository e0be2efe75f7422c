// A sweep row from one pipeline run: what `stairplan sweep` and the Python sweep record per point.
#pragma once

#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/sweep/sweep_runner.h"

namespace stairplan {

/// The row of `point` planned (and validated) as `result`: "valid" or "invalid" with the first
/// violation, "infeasible" with the planner's reason, or "planned" when not validated.
SweepRow PipelineSweepRow(const SweepPoint& point, const PipelineResult& result);

}  // namespace stairplan
