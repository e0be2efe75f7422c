// What a gait's MuJoCo test asks of an executed plan: success at the plan's own pace, every landing
// touched inside its step region, no link but the feet on the stairs, the robot up or down the
// flight.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/planning/plan.h"
#include "stairplan/simulation/sim_outcome.h"

namespace stairplan::testing {

inline void CheckExecutedCleanly(const SimulationOutcome& o, const Plan& plan, const Staircase& stairs) {
  INFO(ToString(o.status) << " / " << o.FirstCause() << ", roll " << o.max_roll);
  CHECK(o.time_scale == 1.0);
  CHECK(o.status == SimStatus::kSuccess);
  CHECK(o.Passed());
  CHECK(o.landings.size() == plan.footsteps.size());
  for (const FootLanding& l : o.landings) {
    CAPTURE(l.leg, l.t_planned);
    CHECK(l.touched);
    CHECK(l.in_step_region);
  }
  CHECK(std::abs(o.final_base_W.z() - plan.body.front().z) > 0.8 * stairs.total_rise());
}

}  // namespace stairplan::testing
