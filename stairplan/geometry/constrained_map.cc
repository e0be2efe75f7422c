#include "stairplan/geometry/constrained_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

struct Band {
  double lo = 0.0;
  double hi = 0.0;
};

// The step band of one surface along x. Treads lose a margin at the walking edge and at the
// riser side; which end is which depends on the direction of travel. Landings only lose the
// margin at the end that touches the flight. Facing backwards, the legs fold the other way and
// the seed's middle fraction of each tread is used instead.
Band StepBand(const Staircase& stairs, const StairSurface& s, Facing facing, const ConstrainedMapSettings& m) {
  const bool up = stairs.direction() == TravelDirection::kUp;
  const bool first = s.index == 0;
  const bool last = s.index == stairs.surface_count() - 1;
  // Ascending, a surface starts at its own nosing (walking edge) and ends below the next riser.
  // Descending, it starts below the riser of the surface above and ends at its own nosing.
  const double begin_margin = first ? 0.0 : (up ? m.edge_margin : m.riser_margin);
  const double end_margin = last ? 0.0 : (up ? m.riser_margin : m.edge_margin);
  Band band{s.x_begin + begin_margin, s.x_end - end_margin};
  if (facing == Facing::kBackward && !first && !last) {
    const double middle = 0.5 * (s.x_begin + s.x_end);
    const double half = 0.5 * m.backward_middle_fraction * (s.x_end - s.x_begin);
    band = {middle - half, middle + half};  // replaces the forward margins on treads
  }
  return band;
}

RegionKind BandKind(const Staircase& stairs, bool at_begin) {
  const bool up = stairs.direction() == TravelDirection::kUp;
  return (up == at_begin) ? RegionKind::kEdge : RegionKind::kRiser;
}

}  // namespace

const char* ToString(Facing facing) { return facing == Facing::kForward ? "forward" : "backward"; }

const char* ToString(RegionKind kind) {
  switch (kind) {
    case RegionKind::kEdge: return "edge";
    case RegionKind::kRiser: return "riser";
    case RegionKind::kSide: return "side";
    case RegionKind::kRobot: return "robot";
    case RegionKind::kData: return "data";
  }
  return "unknown";
}

void ConstrainedMapSettings::Validate() const {
  RequireInRange("edge_margin", edge_margin, 0.0, 1.0);
  RequireInRange("riser_margin", riser_margin, 0.0, 1.0);
  RequireInRange("side_margin", side_margin, 0.0, 5.0);
  RequireInRange("backward_middle_fraction", backward_middle_fraction, 0.0, 1.0);
  RequireInRange("min_region_depth", min_region_depth, 0.0, 1.0);
}

ConstrainedMap ConstrainedMap::FromStaircase(const Staircase& stairs, Facing facing, const ConstrainedMapSettings& settings) {
  settings.Validate();
  ConstrainedMap map;
  map.facing_ = facing;
  map.direction_ = stairs.direction();
  const double hw = stairs.half_width();
  const double y_lo = -hw + settings.side_margin;
  const double y_hi = hw - settings.side_margin;
  for (const StairSurface& s : stairs.surfaces()) {
    StairRegions regions;
    regions.index = s.index;
    regions.z = s.z;
    regions.surface = stairs.TreadPolygon(s.index);
    const Band band = StepBand(stairs, s, facing, settings);
    const bool usable = band.hi - band.lo >= settings.min_region_depth && y_hi > y_lo;
    if (usable) regions.step_region = Rectangle(band.lo, band.hi, y_lo, y_hi, s.z);
    // A tread too shallow for a step region is split at its middle between the two reasons.
    const double middle = 0.5 * (s.x_begin + s.x_end);
    const double cut_lo = usable ? band.lo : middle;
    const double cut_hi = usable ? band.hi : middle;
    if (cut_lo > s.x_begin) {
      regions.collision_regions.push_back({Rectangle(s.x_begin, cut_lo, -hw, hw, s.z), BandKind(stairs, true)});
    }
    if (s.x_end > cut_hi) {
      regions.collision_regions.push_back({Rectangle(cut_hi, s.x_end, -hw, hw, s.z), BandKind(stairs, false)});
    }
    if (settings.side_margin > 0.0) {
      regions.collision_regions.push_back({Rectangle(s.x_begin, s.x_end, -hw, -hw + settings.side_margin, s.z), RegionKind::kSide});
      regions.collision_regions.push_back({Rectangle(s.x_begin, s.x_end, hw - settings.side_margin, hw, s.z), RegionKind::kSide});
    }
    map.stairs_.push_back(std::move(regions));
  }
  return map;
}

const StairRegions& ConstrainedMap::stair(int index) const {
  if (index < 0 || index >= size()) {
    throw std::out_of_range("ConstrainedMap::stair: index " + std::to_string(index) + " out of range");
  }
  return stairs_[static_cast<std::size_t>(index)];
}

int ConstrainedMap::StairAt(const Eigen::Vector2d& p) const {
  for (const StairRegions& s : stairs_) {
    if (s.surface.Contains(p, 0.0)) return s.index;
  }
  return -1;
}

bool ConstrainedMap::InStepRegion(int index, const Eigen::Vector2d& p, double tol) const {
  const StairRegions& s = stair(index);
  return !s.step_region.empty() && s.step_region.Contains(p, tol);
}

bool ConstrainedMap::InCollisionRegion(int index, const Eigen::Vector2d& p) const {
  const StairRegions& s = stair(index);
  return std::any_of(s.collision_regions.begin(), s.collision_regions.end(),
                     [&](const CollisionRegion& r) { return r.polygon.Contains(p, 0.0); });
}

int ConstrainedMap::NearestStepRegion(const Eigen::Vector2d& p, double* distance) const {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (const StairRegions& s : stairs_) {
    if (s.step_region.empty()) continue;
    const double d = s.step_region.Distance(p);
    if (d < best_d) {
      best_d = d;
      best = s.index;
    }
  }
  if (distance != nullptr) *distance = best_d;
  return best;
}

void ConstrainedMap::AddCollisionBand(int index, double x0, double x1, RegionKind kind) {
  if (!(x1 > x0)) throw std::invalid_argument("ConstrainedMap::AddCollisionBand: need x0 < x1");
  StairRegions& s = stairs_.at(static_cast<std::size_t>(index));
  const auto [smin, smax] = std::minmax_element(s.surface.vertices.begin(), s.surface.vertices.end(),
                                                [](const auto& a, const auto& b) { return a.y() < b.y(); });
  s.collision_regions.push_back({Rectangle(x0, x1, smin->y(), smax->y(), s.z), kind});
  if (s.step_region.empty()) return;
  const auto [lo, hi] = s.step_region.XExtent();
  double ylo = std::numeric_limits<double>::infinity(), yhi = -ylo;
  for (const auto& v : s.step_region.vertices) {
    ylo = std::min(ylo, v.y());
    yhi = std::max(yhi, v.y());
  }
  if (x1 <= lo || x0 >= hi) return;
  const double left = std::max(0.0, x0 - lo);   // what stays before the band
  const double right = std::max(0.0, hi - x1);  // what stays after it
  if (left <= 0.0 && right <= 0.0) {
    s.step_region = Polygon2{};
  } else if (left >= right) {
    s.step_region = Rectangle(lo, x0, ylo, yhi, s.z);
  } else {
    s.step_region = Rectangle(x1, hi, ylo, yhi, s.z);
  }
}

}  // namespace stairplan
