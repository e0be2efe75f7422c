// How far a regular staircase fitted to data (a cloud's levels and edges, footfalls' treads and
// edges) may be from the true one at its nosings, the stair geometry a leg's clearance depends on.
// Both fitters put a least-squares line through the levels' heights and one through the edges'
// positions against the step index; a nosing k is (edge k, level k). Its fitted position errs by
// the lines' standard errors at k: in the world (offset and slope) and relative to the fitted
// origin, the first edge and the lowest level where a plan's frame sits (the slope's error
// accumulated over the steps between). The bound is the largest of these over the flight, each
// line's standard error (from its residuals' scale, never below the samples' own error where the
// fitter knows it) taken twice: a coverage of 2, about 95 % for each line's normal error. The
// bound is what the data say about their scatter: a bias common to every sample (a sensor that
// reads every tread 1 mm low) is not in it.
#pragma once

#include <vector>

namespace stairplan {

/// Samples of one quantity (a level's height, an edge's position along the flight) against the
/// step index, as a fitter put a line through them.
struct IndexedSamples {
  std::vector<double> index;  ///< each sample's step index (levels: 0 the lowest; edges: k before level k)
  std::vector<double> value;  ///< [m]
  /// Each sample's own standard error where the fitter knows it apart from the line (a tread's
  /// height from its footfalls' scatter) [m]; the residuals' scale is never taken below it. 0: unknown.
  double sample_sigma = 0.0;
};

/// The bound [m] on how far each fitted nosing k = 1..`steps` (edge k at level k) may be from the
/// true one, in the world and relative to the fitted first edge (either end of the flight) and
/// lowest level, with `coverage` standard errors. Throws std::invalid_argument for mismatched
/// sizes, fewer than two samples of a line or non-finite values.
double NosingUncertainty(const IndexedSamples& levels, const IndexedSamples& edges, int steps, double coverage = 2.0);

}  // namespace stairplan
