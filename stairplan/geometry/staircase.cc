#include "stairplan/geometry/staircase.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

// Depth of the solid under the lowest surface, so blocks have volume for collision queries.
constexpr double kBaseDepth = 0.10;

std::string Num(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

void RequireRange(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value)) throw FieldError(field, "must be a finite number (got " + Num(value) + ")");
  if (value <= lo || value > hi) {
    throw FieldError(field, "must be in (" + Num(lo) + ", " + Num(hi) + "] m (got " + Num(value) + ")");
  }
}

void RequireList(const std::string& field, const std::vector<double>& values, std::size_t size, double lo, double hi) {
  if (values.empty()) return;
  if (values.size() != size) {
    throw FieldError(field, "needs " + std::to_string(size) + " entries (got " + std::to_string(values.size()) + ")");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    RequireRange(field + "[" + std::to_string(i) + "]", values[i], lo, hi);
  }
}

}  // namespace

const char* ToString(TravelDirection direction) { return direction == TravelDirection::kUp ? "up" : "down"; }

void StairSpec::Validate() const {
  if (steps < 1 || steps > 200) {
    throw FieldError("steps", "must be between 1 and 200 (got " + std::to_string(steps) + ")");
  }
  RequireRange("rise", rise, 0.0, 0.6);
  RequireRange("run", run, 0.0, 3.0);
  RequireRange("width", width, 0.0, 20.0);
  RequireRange("landing_before", landing_before, 0.0, 50.0);
  RequireRange("landing_after", landing_after, 0.0, 50.0);
  RequireRange("nosing_thickness", nosing_thickness, 0.0, 0.2);
  // A bound larger than a nosing's thickness says the stairs are not known well enough to plan on.
  if (!std::isfinite(uncertainty) || uncertainty < 0.0 || uncertainty > 0.1) {
    throw FieldError("uncertainty", "must be in [0, 0.1] m (got " + Num(uncertainty) + ")");
  }
  if (!std::isfinite(nosing) || nosing < 0.0) {
    throw FieldError("nosing", "must be a finite number >= 0 (got " + Num(nosing) + ")");
  }
  RequireList("rises", rises, static_cast<std::size_t>(steps), 0.0, 0.6);
  RequireList("runs", runs, static_cast<std::size_t>(steps - 1), 0.0, 3.0);
  const double min_run = runs.empty() ? run : *std::min_element(runs.begin(), runs.end());
  if (steps > 1 && nosing >= 0.5 * min_run) {
    throw FieldError("nosing", "must be less than half the shortest run (" + Num(0.5 * min_run) + " m; got " + Num(nosing) + ")");
  }
  const double min_rise = rises.empty() ? rise : *std::min_element(rises.begin(), rises.end());
  if (nosing > 0.0 && nosing_thickness >= min_rise) {
    throw FieldError("nosing_thickness", "must be less than the lowest rise (" + Num(min_rise) + " m)");
  }
}

Staircase::Staircase(const StairSpec& spec) : spec_(spec) {
  spec_.Validate();
  const auto n = static_cast<std::size_t>(spec_.steps);
  rises_ = spec_.rises.empty() ? std::vector<double>(n, spec_.rise) : spec_.rises;
  runs_ = spec_.runs.empty() ? std::vector<double>(n - 1, spec_.run) : spec_.runs;
  spec_.rises = rises_;
  spec_.runs = runs_;
  for (double r : rises_) total_rise_ += r;

  const bool up = spec_.direction == TravelDirection::kUp;
  // Riser faces in travel order; the walkable boundary is the nosing front, which overhangs the
  // lower surface: backwards when ascending, forwards when descending.
  double x_riser = 0.0;
  double z = up ? 0.0 : total_rise_;
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) x_riser += runs_[k - 1];
    const double z_next = up ? z + rises_[k] : z - rises_[k];
    StairEdge edge;
    edge.index = static_cast<int>(k) + 1;
    edge.x_riser = x_riser;
    edge.x_nose = up ? x_riser - spec_.nosing : x_riser + spec_.nosing;
    edge.z_low = std::min(z, z_next);
    edge.z_high = std::max(z, z_next);
    edges_.push_back(edge);
    z = z_next;
  }
  double x_begin = -spec_.landing_before;
  z = up ? 0.0 : total_rise_;
  for (std::size_t k = 0; k <= n; ++k) {
    StairSurface surface;
    surface.index = static_cast<int>(k);
    surface.x_begin = x_begin;
    surface.x_end = k < n ? edges_[k].x_nose : edges_.back().x_riser + spec_.landing_after;
    surface.z = z;
    surfaces_.push_back(surface);
    if (k < n) {
      x_begin = edges_[k].x_nose;
      z = up ? z + rises_[k] : z - rises_[k];
    }
  }
}

const StairSurface& Staircase::surface(int index) const {
  if (index < 0 || index >= surface_count()) {
    throw std::out_of_range("Staircase::surface: index " + std::to_string(index) + " out of range");
  }
  return surfaces_[static_cast<std::size_t>(index)];
}

int Staircase::SurfaceIndexAt(double x, double y) const {
  if (!std::isfinite(x) || !std::isfinite(y) || std::abs(y) > half_width()) return -1;
  if (x < x_min() || x > x_max()) return -1;
  // Surfaces are sorted along x; the first whose end lies beyond x holds it.
  const auto it = std::upper_bound(surfaces_.begin(), surfaces_.end(), x,
                                   [](double value, const StairSurface& s) { return value < s.x_end; });
  return it == surfaces_.end() ? surface_count() - 1 : it->index;
}

double Staircase::HeightAt(double x, double y) const {
  const int index = SurfaceIndexAt(x, y);
  return index < 0 ? std::numeric_limits<double>::quiet_NaN() : surfaces_[static_cast<std::size_t>(index)].z;
}

Polygon2 Staircase::TreadPolygon(int index) const {
  const StairSurface& s = surface(index);
  return Rectangle(s.x_begin, s.x_end, -half_width(), half_width(), s.z);
}

std::vector<Box3> Staircase::Solids() const {
  std::vector<Box3> solids;
  const double z_base = -kBaseDepth;  // the lowest surface is at z = 0 either way
  const double hw = half_width();
  for (int k = 0; k < surface_count(); ++k) {
    const double x0 = k == 0 ? x_min() : edges_[static_cast<std::size_t>(k - 1)].x_riser;
    const double x1 = k < steps() ? edges_[static_cast<std::size_t>(k)].x_riser : x_max();
    Box3 block;
    block.min = {x0, -hw, z_base};
    block.max = {x1, hw, surfaces_[static_cast<std::size_t>(k)].z};
    block.kind = SolidKind::kBlock;
    block.surface_index = k;
    solids.push_back(block);
  }
  if (spec_.nosing <= 0.0) return solids;
  for (const StairEdge& e : edges_) {
    Box3 lip;
    lip.min = {std::min(e.x_riser, e.x_nose), -hw, e.z_high - spec_.nosing_thickness};
    lip.max = {std::max(e.x_riser, e.x_nose), hw, e.z_high};
    lip.kind = SolidKind::kNosing;
    lip.surface_index = e.index;
    solids.push_back(lip);
  }
  return solids;
}

}  // namespace stairplan
