// Pipeline options with the body optimisation, as `stairplan plan --body qp` plans: the leg rows
// of LegRowBodySettings() (the planner issue #18 makes the default; tested while it is opt-in).
#pragma once

#include "planning/plan_pipeline.h"

namespace stairplan::testing {

inline PipelineOptions LegRowPipeline() {
  PipelineOptions options;
  options.body = BodySource::kRecedingHorizonQp;
  return options;
}

// The same rows on knots 25 ms apart over the same 1 s horizon, with BodyPlannerSettings' trust
// regions: the configuration Unitree Go1's descents plan valid on (with the 50 ms knots the
// default stairs' put a front leg on a nosing at 9.8 s and the low stairs' find no valid body).
inline PipelineOptions FineKnotLegRowPipeline() {
  PipelineOptions options = LegRowPipeline();
  const BodyPlannerSettings defaults;
  options.body_qp.knots = 40;
  options.body_qp.knot_dt = 0.025;
  options.body_qp.trust_shift = defaults.trust_shift;
  options.body_qp.trust_lateral = defaults.trust_lateral;
  options.body_qp.trust_pitch = defaults.trust_pitch;
  return options;
}

}  // namespace stairplan::testing
