// A smooth stand-in for the stairs under the body: a piecewise-linear line through the middle of
// every tread (the stairs' pitch line), flat over the landings. The body is carried at a fixed
// height above it, so body height and pitch change continuously instead of jumping at each edge.
#pragma once

#include <vector>

#include "stairplan/geometry/constrained_map.h"

namespace stairplan {

/// The stairs' smoothed pitch line under the body: piecewise linear through the treads' middles,
/// flat over the landings.
class GroundProfile {
 public:
  GroundProfile() = default;
  /// The line through the constrained map's surfaces (their top polygons and heights).
  static GroundProfile FromMap(const ConstrainedMap& map);

  /// Height of the line at x; flat beyond the ends. Allocation-free.
  double HeightAt(double x) const;
  /// The line's knots along x [m].
  const std::vector<double>& knots_x() const { return xs_; }
  /// The line's knot heights [m].
  const std::vector<double>& knots_z() const { return zs_; }

 private:
  std::vector<double> xs_;
  std::vector<double> zs_;
};

}  // namespace stairplan
