// The stairs as a model: per-step rises and runs, nosing, width, landings, direction of travel.
// The robot always travels along +x; ascending stairs rise with x, descending ones fall with x.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/shapes.h"

namespace stairplan {

/// Which way the robot travels the stairs: up or down.
enum class TravelDirection { kUp, kDown };

/// Returns "up" or "down".
const char* ToString(TravelDirection direction);

/// What a user says about the stairs. Per-step lists, when given, override the scalars and are in
/// travel order: `rises` has one entry per step (riser), `runs` one per tread between risers.
struct StairSpec {
  int steps = 7;                  ///< number of risers
  double rise = 0.17;             ///< riser height [m]
  double run = 0.27;              ///< tread going, nosing to nosing [m]
  double nosing = 0.02;           ///< overhang of a tread over the riser below [m]
  double width = 1.0;             ///< stair width across y [m]
  double landing_before = 1.2;    ///< flat ground before the first riser [m]
  double landing_after = 1.2;     ///< flat ground after the last riser [m]
  double nosing_thickness = 0.03; ///< vertical thickness of the nosing lip [m]
  std::vector<double> rises;      ///< optional per-step rises (size == steps)
  std::vector<double> runs;       ///< optional per-tread runs (size == steps - 1)
  TravelDirection direction = TravelDirection::kUp;  ///< which way the robot travels: up or down the stairs
  /// How far the true nosings may be from these stairs' [m]: 0 for stairs known exactly, else the
  /// bound the estimate that produced them derived (StairModel::uncertainty: a cloud's fit, footfalls).
  /// Planners keep it as clearance on top of their own margins (WithStairUncertainty,
  /// stairplan/pipeline/plan_pipeline.h); the geometry does not change with it.
  double uncertainty = 0.0;

  /// Throws std::invalid_argument naming the offending field (e.g. "run", "rises[3]").
  void Validate() const;
};

/// One walkable surface: the bottom landing (index 0), a tread (1..steps-1) or the top landing
/// (index steps). Its top is the rectangle [x_begin, x_end] x [-width/2, width/2] at height z.
struct StairSurface {
  int index = 0;  ///< in travel order: 0 the landing the robot starts on, steps the one it ends on
  double x_begin = 0.0;  ///< where the visible top starts along travel [m]
  double x_end = 0.0;    ///< where the visible top ends along travel [m]
  double z = 0.0;        ///< height of the top [m]
};

/// An edge between surface k-1 and surface k (k = 1..steps): the riser face and the nosing lip.
struct StairEdge {
  int index = 0;          ///< k: the edge lies before surface k
  double x_riser = 0.0;   ///< the riser face [m]
  double x_nose = 0.0;    ///< the front of the nosing lip (the walking edge) [m]
  double z_low = 0.0;     ///< the lower surface's height [m]
  double z_high = 0.0;    ///< the higher surface's height [m]
};

/// A staircase resolved from a StairSpec: immutable, cheap to query.
class Staircase {
 public:
  /// Validates `spec` (throws std::invalid_argument naming the field) and resolves the geometry.
  explicit Staircase(const StairSpec& spec);

  /// The spec it was resolved from.
  const StairSpec& spec() const { return spec_; }
  /// Up or down: the way the robot travels along +x.
  TravelDirection direction() const { return spec_.direction; }
  /// Number of risers.
  int steps() const { return spec_.steps; }
  /// Number of surfaces: landings included (steps + 1).
  int surface_count() const { return static_cast<int>(surfaces_.size()); }
  /// Surface `index` (0 .. steps); throws std::out_of_range for a bad index.
  const StairSurface& surface(int index) const;
  /// Every surface, in travel order.
  const std::vector<StairSurface>& surfaces() const { return surfaces_; }
  /// Every edge (riser and nosing), in travel order.
  const std::vector<StairEdge>& edges() const { return edges_; }
  /// Height of riser `step` (0-based, travel order) [m].
  double rise(int step) const { return rises_.at(static_cast<std::size_t>(step)); }
  /// Half the stair width [m].
  double half_width() const { return 0.5 * spec_.width; }
  /// Where the first landing starts along travel [m].
  double x_min() const { return surfaces_.front().x_begin; }
  /// Where the last landing ends along travel [m].
  double x_max() const { return surfaces_.back().x_end; }
  /// Height difference between the two landings [m].
  double total_rise() const { return total_rise_; }

  /// Height of the walkable surface at (x, y); NaN outside the stairs' footprint.
  double HeightAt(double x, double y) const;
  /// Index of the surface under (x, y), or -1 outside the footprint.
  int SurfaceIndexAt(double x, double y) const;
  /// The top of surface `index` as a convex polygon (counter-clockwise, at its height).
  Polygon2 TreadPolygon(int index) const;
  /// Solid boxes of the stairs: one block under each surface plus one nosing lip per edge.
  std::vector<Box3> Solids() const;

 private:
  StairSpec spec_;
  std::vector<double> rises_;
  std::vector<double> runs_;
  std::vector<StairSurface> surfaces_;
  std::vector<StairEdge> edges_;
  double total_rise_ = 0.0;
};

}  // namespace stairplan
