// The pipeline options of the receding-horizon body QP with leg rows, as the README's scorecard
// flags set them (--body qp, stance_rows=1, stability_margin=0.03, hip_height_fraction=0.6,
// max_shift=0.15): the planner issue #18 makes the default, tested while it is opt-in.
#pragma once

#include "planning/plan_pipeline.h"

namespace stairplan::testing {

inline PipelineOptions LegRowPipeline() {
  PipelineOptions options;
  options.body = BodySource::kRecedingHorizonQp;
  options.body_qp.stance_rows = true;
  options.body_qp.stability_margin = 0.03;
  options.body_qp.hip_height_fraction = 0.6;
  options.body_qp.max_shift = 0.15;
  return options;
}

}  // namespace stairplan::testing
