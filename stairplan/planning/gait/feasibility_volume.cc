#include "stairplan/planning/gait/feasibility_volume.h"

#include <cmath>

namespace stairplan {

DimensionlessVerdict EvaluateDimensionless(const DimensionlessDesign& x) {
  DimensionlessVerdict v;
  const bool valid = std::isfinite(x.run) && std::isfinite(x.rise) && std::isfinite(x.max_leg) && x.run > 0.0 &&
                     x.rise > 0.0 && x.max_leg > 0.0 && std::isfinite(x.buffer) && x.buffer >= 0.0 && x.buffer < 1.0;
  if (!valid) return v;
  const double p = x.buffer;
  const double cl = std::hypot(x.run, x.rise);  // CL / BL
  const double l2 = x.max_leg * x.max_leg;
  const double half_cl2 = 0.25 * cl * cl;
  const double slope = (2.0 - p) * x.run / x.rise;
  const double front = (3.0 - 0.5 * p) * cl - 1.0;  // from (11): must not be negative before squaring
  const double hind = 1.0 - 0.5 * p * cl;           // from (12): likewise
  v.c14 = front >= 0.0 && l2 <= half_cl2 + front * front / (slope * slope);
  v.c15 = hind >= 0.0 && l2 <= half_cl2 + hind * hind / (slope * slope);
  v.c16 = x.max_leg >= 0.5 * cl * cl / x.run;
  v.in_body_range = cl < 1.0 && 2.0 * cl > 1.0;
  return v;
}

}  // namespace stairplan
