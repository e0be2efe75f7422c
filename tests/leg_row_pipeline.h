// Pipeline options with the body optimisation and the leg rows of LegRowBodySettings(), as
// `stairplan plan` plans by default: named, so that tests of the rows keep them whatever the
// defaults become.
#pragma once

#include "stairplan/pipeline/plan_pipeline.h"

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

// The quasi-static path with its posture retries and the crawl's pairs sequence: how `plan`
// planned before the body optimisation (`plan --body path --crawl-sequence pairs`), for the tests
// of the baseline's own mechanisms (posture fit, retries, foothold search).
inline PipelineOptions PathBaselinePipeline() {
  PipelineOptions options;
  options.body = BodySource::kQuasiStaticPath;
  options.crawl.sequence = CrawlSequence::kPairs;
  return options;
}

}  // namespace stairplan::testing
