// The optimality measures of a QP solution as qpbenchmark defines them (qpsolvers' Solution:
// primal_residual, dual_residual, duality_gap), for the two-sided rows and bounds of a Program,
// and its success test: a solver's "solved" whose three measures are all below a tolerance
// (qpbenchmark's high accuracy is 1e-9, its mid accuracy 1e-6; absolute, not relative).
//
//   r_p = max(0, lower - A x, A x - upper, x_lower - x, x - x_upper)      (infinite sides skipped)
//   r_d = |H x + g + A' y + z|_inf
//   r_g = |x' H x + g' x + sum_i (upper_i max(y_i, 0) + lower_i min(y_i, 0)) + (same over bounds, z)|
//
// with SolveResult's duals (y row_duals, z bound_duals: <= 0 on an active lower side, >= 0 on an
// active upper side). For one-sided rows G x <= h and equalities A x = b this is qpbenchmark's
// gap |x'Px + q'x + h'z + b'y + ...| term for term; like qpbenchmark's sums over the finite lb
// and ub, infinite sides add nothing (a solver's round-off dual on a free variable is no gap).
#pragma once

#include <cmath>

#include "stairplan/optim/program.h"
#include "stairplan/optim/solve_result.h"

namespace stairplan::optim {

/// qpbenchmark's three measures of one solution (infinite when the result has no finite x).
struct QpResiduals {
  double primal = kInf;  ///< r_p: largest violation of a row or bound
  double dual = kInf;  ///< r_d: |H x + g + A' y + z|_inf
  double gap = kInf;  ///< r_g: the duality gap
  /// All three below `tolerance` (with a kSolved status, qpbenchmark's success).
  bool Within(double tolerance) const { return primal < tolerance && dual < tolerance && gap < tolerance; }
};

/// One constraint's term of r_g: upper max(dual, 0) + lower min(dual, 0), an infinite side
/// adding nothing (as qpbenchmark sums over the finite lb and ub). Inline: the interior-point
/// solver evaluates it for every constraint at every iteration.
inline double GapSupportTerm(double dual, double lower, double upper) {
  if (dual > 0 && std::isfinite(upper)) return upper * dual;
  if (dual < 0 && std::isfinite(lower)) return lower * dual;
  return 0.0;
}

/// The measures of `result` on the quadratic program `program` (sizes must match).
QpResiduals ComputeQpResiduals(const Program& program, const SolveResult& result);

}  // namespace stairplan::optim
