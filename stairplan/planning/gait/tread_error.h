// How much tread depth may differ from the design's W before the crawl loses its footing (Chen, Ko,
// Li, Lin 2012, "Stair Climbing in a Quadruped Robot", "Error Adaptation", eqs. (17)-(19)). Errors
// add up from step to step because the gait runs open loop, so a staircase is checked on the
// cumulative error.
#pragma once

#include <vector>

#include "stairplan/planning/gait/gait_design.h"

namespace stairplan {

/// The permitted range of a tread depth error: lower < dW < upper [m].
struct TreadErrorTolerance {
  /// a: the right foot's contact offset (a_min); a longer tread pushes the foot off the edge.
  double upper = 0.0;
  /// Eq. (17)'s right side with b = a_max (the left foot's contact offset) and D_s from eq. (18).
  double lower = 0.0;
  /// No error is tolerated: eq. (17) gives lower >= upper, or the bounds are NaN (no D_s > 0).
  bool empty() const { return !(lower < upper); }
};

/// Eq. (17) for the design's stairs, leg and hip clearance. The paper's example (W = 27 cm,
/// H = 17 cm, l_max = 21 cm, d = 8.5 cm) gives 2.9 > dW > -12.05 cm. Both bounds are NaN when the
/// design has no D_s > 0 (condition (10) fails).
TreadErrorTolerance TreadDepthTolerance(const GaitDesign& design, double run, double rise);

/// The cumulative check of eq. (19) over a flight.
struct CumulativeTreadError {
  std::vector<double> cumulative;  ///< dW_t after each step: the running sum of the errors [m]
  int first_violation = -1;        ///< the first step whose dW_t leaves the range, -1 when none
  /// True when the cumulative error stays within the range at every step.
  bool within() const { return first_violation < 0; }
};

/// Sums per-step tread errors (each tread's depth minus the design's W) and finds the first step
/// whose running sum leaves `tolerance`. Throws std::invalid_argument on a non-finite error,
/// naming its index.
CumulativeTreadError CheckCumulativeTreadError(const std::vector<double>& errors, const TreadErrorTolerance& tolerance);

}  // namespace stairplan
