#include "stairplan/perception/gap_fill.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

// The nearest measured cell from (ix, iy) walking along (dx, dy), within max_steps.
// `top` is the highest point of that cell and the measured ones just beyond it: seen from below,
// a nosing's lip hides the top of its riser, so the first cell can be the lip's underside, and
// a lip's face is sampled sparsely, so its highest point is nearer its top than the cell's mean.
constexpr int kLipCells = 3;
struct Hit {
  bool found = false;
  int steps = 0;
  float height = 0.0f;
  float top = 0.0f;
};

Hit Walk(const HeightMap& map, int ix, int iy, int dx, int dy, int max_steps) {
  for (int s = 1; s <= max_steps; ++s) {
    const int x = ix + s * dx, y = iy + s * dy;
    if (!map.Inside(x, y)) break;
    if (map.state(x, y) != CellState::kMeasured) continue;
    Hit hit{true, s, map.height(x, y), map.top(x, y)};
    for (int k = 1; k <= kLipCells; ++k) {
      const int bx = x + k * dx, by = y + k * dy;
      if (map.Inside(bx, by) && map.state(bx, by) == CellState::kMeasured) hit.top = std::max(hit.top, map.top(bx, by));
    }
    return hit;
  }
  return {};
}

}  // namespace

void GapFillSettings::Validate() const {
  if (!(contrast > 0.0 && contrast < 10.0)) throw FieldError("contrast", "must be in (0, 10) m");
  if (!(max_gap > 0.0 && max_gap < 100.0)) throw FieldError("max_gap", "must be in (0, 100) m");
  if (!(poor_span >= 0.0) || !std::isfinite(poor_span)) throw FieldError("poor_span", "must be >= 0");
  if (smoothing_sweeps < 0 || smoothing_sweeps > 10000) throw FieldError("smoothing_sweeps", "must be in [0, 10000]");
}

GapFillReport FillGaps(HeightMap& map, const GapFillSettings& settings) {
  settings.Validate();
  const int max_steps = static_cast<int>(std::ceil(settings.max_gap / map.resolution()));
  const double res = map.resolution();
  std::vector<std::pair<int, int>> smooth_cells;
  GapFillReport report;
  // Decide every cell from the measured data only, so the result does not depend on visiting order.
  struct Fill {
    int ix, iy;
    float height;
    CellState state;
  };
  std::vector<Fill> fills;
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      if (map.state(ix, iy) != CellState::kUnknown) continue;
      const Hit xm = Walk(map, ix, iy, -1, 0, max_steps), xp = Walk(map, ix, iy, 1, 0, max_steps);
      const Hit ym = Walk(map, ix, iy, 0, -1, max_steps), yp = Walk(map, ix, iy, 0, 1, max_steps);
      const bool x_pair = xm.found && xp.found && (xm.steps + xp.steps) * res <= settings.max_gap;
      const bool y_pair = ym.found && yp.found && (ym.steps + yp.steps) * res <= settings.max_gap;
      if (!x_pair && !y_pair) continue;  // no bridge across the hole: leave it unknown
      const float x_jump = x_pair ? std::abs(xm.height - xp.height) : 0.0f;
      const float y_jump = y_pair ? std::abs(ym.height - yp.height) : 0.0f;
      if (std::max(x_jump, y_jump) > settings.contrast) {
        // Near-far contrast: the high side hides the low one, which continues flat.
        const float low = x_jump >= y_jump ? std::min(xm.top, xp.top) : std::min(ym.top, yp.top);
        fills.push_back({ix, iy, low, CellState::kOccluded});
        continue;
      }
      // No contrast: linear interpolation along each bridge, the shorter bridge weighted more.
      double sum = 0.0, weight = 0.0;
      int shortest = 1 << 30;
      if (x_pair) {
        const int span = xm.steps + xp.steps;
        const double t = static_cast<double>(xm.steps) / span;
        sum += ((1.0 - t) * xm.height + t * xp.height) / span;
        weight += 1.0 / span;
        shortest = std::min(shortest, span);
      }
      if (y_pair) {
        const int span = ym.steps + yp.steps;
        const double t = static_cast<double>(ym.steps) / span;
        sum += ((1.0 - t) * ym.height + t * yp.height) / span;
        weight += 1.0 / span;
        shortest = std::min(shortest, span);
      }
      const bool poor = shortest * res > settings.poor_span;
      fills.push_back({ix, iy, static_cast<float>(sum / weight), poor ? CellState::kPoor : CellState::kSmoothed});
    }
  }
  for (const Fill& f : fills) {
    map.Set(f.ix, f.iy, f.height, f.state);
    if (f.state == CellState::kOccluded) {
      ++report.occluded;
    } else {
      ++report.smoothed;
      if (f.state == CellState::kPoor) ++report.poor;
      smooth_cells.emplace_back(f.ix, f.iy);
    }
  }
  // Relax the smoothly filled cells towards the mean of their neighbours (Gauss-Seidel on the
  // Laplace equation with the measured and flat-filled cells as boundary): planes stay planes.
  for (int sweep = 0; sweep < settings.smoothing_sweeps; ++sweep) {
    for (const auto& [ix, iy] : smooth_cells) {
      double sum = 0.0;
      int n = 0;
      const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
      for (int k = 0; k < 4; ++k) {
        const int x = ix + dx[k], y = iy + dy[k];
        if (!map.Inside(x, y) || map.state(x, y) == CellState::kUnknown) continue;
        sum += map.height(x, y);
        ++n;
      }
      // Only cells enclosed on all four sides are relaxed; at the rim the interpolation stands.
      if (n == 4) map.Set(ix, iy, static_cast<float>(sum / n), map.state(ix, iy));
    }
  }
  report.unknown = map.CountState(CellState::kUnknown);
  return report;
}

}  // namespace stairplan
