#include "stairplan/planning/step/ground_profile.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace stairplan {
namespace {

using Span = Extent;

}  // namespace

GroundProfile GroundProfile::FromMap(const ConstrainedMap& map) {
  if (map.size() < 1) throw std::invalid_argument("GroundProfile::FromMap: map: has no surfaces");
  GroundProfile g;
  const int n = map.size();
  std::vector<Span> spans;
  for (const StairRegions& s : map.stairs()) {
    if (s.surface.empty()) throw std::invalid_argument("GroundProfile::FromMap: map: surface " + std::to_string(s.index) + " is empty");
    spans.push_back(s.surface.XExtent());
  }
  const auto add = [&](double x, double z) {
    if (!g.xs_.empty() && x <= g.xs_.back()) return;  // keep the knots strictly increasing
    g.xs_.push_back(x);
    g.zs_.push_back(z);
  };
  for (int k = 0; k < n; ++k) {
    const Span& s = spans[static_cast<std::size_t>(k)];
    const double z = map.stair(k).z;
    if (n == 1) {
      add(s.lo, z);
      add(s.hi, z);
    } else if (k == 0) {
      // The landing joins the line half a tread before the first edge, as if it were a tread.
      const Span& next = spans[1];
      const double half = 0.5 * std::min(next.hi - next.lo, s.hi - s.lo);
      add(s.lo, z);
      add(s.hi - half, z);
    } else if (k == n - 1) {
      const Span& previous = spans[static_cast<std::size_t>(k - 1)];
      const double half = 0.5 * std::min(previous.hi - previous.lo, s.hi - s.lo);
      add(s.lo + half, z);
      add(s.hi, z);
    } else {
      add(0.5 * (s.lo + s.hi), z);
    }
  }
  return g;
}

double GroundProfile::HeightAt(double x) const {
  if (xs_.empty()) return 0.0;
  if (x <= xs_.front()) return zs_.front();
  if (x >= xs_.back()) return zs_.back();
  const auto it = std::upper_bound(xs_.begin(), xs_.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - xs_.begin());
  const double t = (x - xs_[i - 1]) / (xs_[i] - xs_[i - 1]);
  return zs_[i - 1] + t * (zs_[i] - zs_[i - 1]);
}

}  // namespace stairplan
