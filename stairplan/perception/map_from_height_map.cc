#include "stairplan/perception/map_from_height_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

using Interval = Extent;

// Merges overlapping intervals.
std::vector<Interval> Merge(std::vector<Interval> v) {
  std::sort(v.begin(), v.end(), [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  std::vector<Interval> out;
  for (const Interval& i : v) {
    if (!out.empty() && i.lo <= out.back().hi) {
      out.back().hi = std::max(out.back().hi, i.hi);
    } else {
      out.push_back(i);
    }
  }
  return out;
}

// Distance along x to the nearest edge (between its nosing and its riser).
double DistanceToEdge(const Staircase& stairs, double x) {
  double best = 1e300;
  for (const StairEdge& e : stairs.edges()) {
    const double lo = std::min(e.x_nose, e.x_riser), hi = std::max(e.x_nose, e.x_riser);
    best = std::min(best, x < lo ? lo - x : (x > hi ? x - hi : 0.0));
  }
  return best;
}

Staircase FittedStaircase(const HeightMap& map, const StairModel& model, const MapFromHeightMapSettings& s) {
  if (model.steps < 1) throw std::invalid_argument("ConstrainedMapFromHeightMap: the stair model has no steps");
  // How far the data reaches before the first and after the last edge, along the travel.
  const Staircase probe = model.ToStaircase(s.travel, s.nosing, 1.0);
  double lo = 0.0, hi = 0.0;
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      if (map.state(ix, iy) == CellState::kUnknown) continue;
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      const Eigen::Vector3d p = model.WorldToStair(Eigen::Vector3d(c.x(), c.y(), 0.0), s.travel, s.nosing);
      if (std::abs(p.y()) > probe.half_width()) continue;
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
  }
  StairSpec spec = probe.spec();
  spec.landing_before = std::clamp(probe.edges().front().x_nose - lo, s.min_landing, s.max_landing);
  spec.landing_after = std::clamp(hi - probe.edges().back().x_riser, s.min_landing, s.max_landing);
  return Staircase(spec);
}

}  // namespace

void MapFromHeightMapSettings::Validate() const {
  margins.Validate();
  if (!(nosing >= 0.0 && nosing < 0.1)) throw FieldError("nosing", "must be in [0, 0.1) m");
  if (!(jump > 0.0 && jump < 1.0)) throw FieldError("jump", "must be in (0, 1) m");
  if (!(edge_dilation >= 0.0 && edge_dilation < 0.5)) throw FieldError("edge_dilation", "must be in [0, 0.5) m");
  if (!(surface_tolerance > 0.0)) throw FieldError("surface_tolerance", "must be positive");
  if (!(min_landing > 0.0 && max_landing >= min_landing && max_landing <= 50.0)) {
    throw FieldError("min_landing/max_landing", "need 0 < min_landing <= max_landing <= 50 m");
  }
}

PerceivedStairs ConstrainedMapFromHeightMap(const HeightMap& map, const StairModel& model, const MapFromHeightMapSettings& settings) {
  settings.Validate();
  const Staircase stairs = FittedStaircase(map, model, settings);
  PerceivedStairs out{stairs, ConstrainedMap::FromStaircase(stairs, settings.facing, settings.margins), 0, 0};
  const bool up = settings.travel == TravelDirection::kUp;
  // A cell's footprint seen in the stairs' frame (rotated): half its diagonal covers it.
  const double half_cell = 0.5 * map.resolution() * std::sqrt(2.0);
  const double edge_reach = half_cell + settings.edge_dilation;
  std::map<std::pair<int, RegionKind>, std::vector<Interval>> bands;
  const auto surface_of = [&](int ix, int iy, Eigen::Vector3d* p_S) {
    const Eigen::Vector2d c = map.CellCenter(ix, iy);
    *p_S = model.WorldToStair(Eigen::Vector3d(c.x(), c.y(), map.height(ix, iy)), settings.travel, settings.nosing);
    return stairs.SurfaceIndexAt(p_S->x(), p_S->y());
  };
  const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      Eigen::Vector3d p;
      const CellState state = map.state(ix, iy);
      if (state == CellState::kUnknown) continue;
      const int k = surface_of(ix, iy, &p);
      if (k < 0) continue;
      const StairSurface& s = stairs.surface(k);
      if (state == CellState::kPoor) {
        bands[{k, RegionKind::kData}].push_back({p.x() - half_cell, p.x() + half_cell});
        continue;
      }
      // An edge: the higher side of a height step between measured neighbours ([0048]:
      // discontinuities). Filled cells take no part: a tread filled flat next to the riser face
      // under a nosing is higher than that face without being an edge, and a sparsely seen
      // nosing next to a filled cell would grow into the tread. Nor do cells on a vertical face
      // (their points spread over more than a jump): their height is no surface's.
      bool edge = false;
      for (int n = 0; n < 4 && !edge && state == CellState::kMeasured; ++n) {
        const int jx = ix + dx[n], jy = iy + dy[n];
        if (!map.Inside(jx, jy) || map.state(jx, jy) != CellState::kMeasured || map.spread(jx, jy) > settings.jump) continue;
        edge = map.height(ix, iy) - map.height(jx, jy) > settings.jump;
      }
      // The stairs' own edges are the analytic map's edge and riser regions already; a height step
      // within reach of one (sparse samples of a riser face look like a low surface; the riser
      // lies a nosing behind the walking edge the model holds) adds nothing.
      const double to_model_edge = DistanceToEdge(stairs, p.x());
      if (edge && to_model_edge > edge_reach + settings.edge_dilation + map.resolution()) {
        // Near the surface's start or end: a walking edge or a riser, depending on the travel.
        const bool at_begin = p.x() - s.x_begin < s.x_end - p.x();
        const RegionKind kind = (up == at_begin) ? RegionKind::kEdge : RegionKind::kRiser;
        // The cell itself, and towards the lower side a nosing may overhang what was seen.
        bands[{k, kind}].push_back(up ? Interval{p.x() - edge_reach, p.x() + half_cell} : Interval{p.x() - half_cell, p.x() + edge_reach});
      }
      if (edge) continue;
      // Off its surface away from the edges (an object on a tread): data says keep off.
      const double from_edges = std::min(p.x() - s.x_begin, s.x_end - p.x());
      // Filled cells count too when far above it (behind an object the fill continues its top),
      // with twice the tolerance; a fill below the surface only says a far riser's top went
      // unsampled between two camera rows, so it is no evidence.
      const double above = p.z() - s.z;
      const bool off_surface = state == CellState::kMeasured ? std::abs(above) > settings.surface_tolerance : above > 2.0 * settings.surface_tolerance;
      if (from_edges > edge_reach + map.resolution() && off_surface) {
        bands[{k, RegionKind::kData}].push_back({p.x() - half_cell, p.x() + half_cell});
      }
    }
  }
  for (auto& [key, intervals] : bands) {
    const auto& [k, kind] = key;
    const StairRegions& regions = out.map.stair(k);
    for (const Interval& i : Merge(intervals)) {
      // Edges outside the step region are already collision regions of the analytic map.
      if (regions.step_region.empty()) break;
      const Interval step = regions.step_region.XExtent();
      if (kind != RegionKind::kData && (i.hi <= step.lo || i.lo >= step.hi)) continue;
      out.map.AddCollisionBand(k, i.lo, i.hi, kind);
      (kind == RegionKind::kData ? out.data_bands : out.edge_bands) += 1;
    }
  }
  return out;
}

}  // namespace stairplan
