#include "stairplan/geometry/stair_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stairplan {
namespace {

// One least-squares line's error: the coverage times a sample's standard error, and the index
// statistics that turn it into the error of the fitted value at an index.
struct LineError {
  double scale = 0.0;  // coverage * max(residual sigma, sample_sigma) [m]
  double n = 0.0;
  double mean_index = 0.0;
  double sxx = 0.0;  // sum of squared index deviations

  // Standard error factor of the fitted value at k (offset and slope), and of the slope alone
  // accumulated from r to k.
  double At(double k) const { return scale * std::sqrt(1.0 / n + (sxx > 0.0 ? (k - mean_index) * (k - mean_index) / sxx : 0.0)); }
  double Between(double r, double k) const { return sxx > 0.0 ? scale * std::abs(k - r) / std::sqrt(sxx) : 0.0; }
};

LineError FitError(const IndexedSamples& s, const char* what, double coverage) {
  if (s.index.size() != s.value.size()) throw std::invalid_argument(std::string("NosingUncertainty: ") + what + ": index and value sizes differ");
  if (s.index.size() < 2) throw std::invalid_argument(std::string("NosingUncertainty: ") + what + ": needs at least two samples");
  if (!std::isfinite(s.sample_sigma) || s.sample_sigma < 0.0) {
    throw std::invalid_argument(std::string("NosingUncertainty: ") + what + ": sample_sigma must be finite and >= 0");
  }
  LineError e;
  e.n = static_cast<double>(s.index.size());
  double mv = 0.0;
  for (std::size_t i = 0; i < s.index.size(); ++i) {
    if (!std::isfinite(s.index[i]) || !std::isfinite(s.value[i])) {
      throw std::invalid_argument(std::string("NosingUncertainty: ") + what + ": sample " + std::to_string(i) + " is not finite");
    }
    e.mean_index += s.index[i];
    mv += s.value[i];
  }
  e.mean_index /= e.n;
  mv /= e.n;
  double cov = 0.0;
  for (std::size_t i = 0; i < s.index.size(); ++i) {
    e.sxx += (s.index[i] - e.mean_index) * (s.index[i] - e.mean_index);
    cov += (s.index[i] - e.mean_index) * (s.value[i] - mv);
  }
  const double slope = e.sxx > 0.0 ? cov / e.sxx : 0.0;
  double ss = 0.0;
  for (std::size_t i = 0; i < s.index.size(); ++i) {
    const double r = s.value[i] - (mv + slope * (s.index[i] - e.mean_index));
    ss += r * r;
  }
  // Two samples fix the line: the residuals say nothing, only the samples' own error does.
  // Residuals of a few samples estimate their scale loosely; Student's t would widen the bound
  // by 1.4-6x for 4-1 degrees of freedom and leave no plan on footfalls: the coverage is 2.
  const int dof = static_cast<int>(s.index.size()) - 2;
  const double residual_sigma = dof >= 1 ? std::sqrt(ss / dof) : 0.0;
  e.scale = coverage * std::max(residual_sigma, s.sample_sigma);
  return e;
}

}  // namespace

double NosingUncertainty(const IndexedSamples& levels, const IndexedSamples& edges, int steps, double coverage) {
  if (steps < 1) throw std::invalid_argument("NosingUncertainty: steps must be >= 1");
  const LineError z = FitError(levels, "levels", coverage);
  const LineError u = FitError(edges, "edges", coverage);
  double bound = 0.0;
  for (int k = 1; k <= steps; ++k) {
    // In the world: both lines' offsets and slopes.
    bound = std::max(bound, std::hypot(u.At(k), z.At(k)));
    // In the plan's frame: from the first edge in travel order (up: edge 1, down: edge `steps`)
    // and the lowest level.
    for (const double first : {1.0, static_cast<double>(steps)}) {
      bound = std::max(bound, std::hypot(u.Between(first, k), z.Between(0.0, k)));
    }
  }
  return bound;
}

}  // namespace stairplan
