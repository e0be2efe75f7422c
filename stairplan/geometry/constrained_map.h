// The constrained map: per stair surface, where a foot may land (the step region) and which parts
// of the surface a leg must avoid (collision regions). Built analytically from a Staircase here;
// perception and the collision module build or refine the same type from data and robot geometry.
#pragma once

#include <string>
#include <vector>

#include "stairplan/geometry/shapes.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// Which way the robot's front faces relative to the direction of travel.
enum class Facing { kForward, kBackward };
/// Returns "forward" or "backward".
const char* ToString(Facing facing);

/// Why a part of a surface is a collision region.
enum class RegionKind {
  kEdge,   ///< near the walking edge (nosing front): the foot would slip off
  kRiser,  ///< near the riser or the nosing above: the leg would hit the stair
  kSide,   ///< near the stair's side
  kRobot,  ///< found by checking the robot's legs against the stairs (collision module)
  kData,   ///< poor or missing sensor data (perception)
};
/// Returns "edge", "riser", "side", "robot" or "data".
const char* ToString(RegionKind kind);

/// Margins of the analytic map [m]. Defaults suit a medium quadruped on building-code stairs.
struct ConstrainedMapSettings {
  double edge_margin = 0.05;      ///< keep-out from the walking edge of a tread
  double riser_margin = 0.07;     ///< keep-out from the riser / nosing above a tread
  double side_margin = 0.10;      ///< keep-out from the stair's sides
  /// Descending backwards, feet go to this middle fraction of each tread (US 2020/0324412 [0047]).
  double backward_middle_fraction = 0.6;
  /// Narrowest step region kept; narrower treads get none (the planner must pass over them).
  double min_region_depth = 0.04;

  /// Throws std::invalid_argument naming the field when a margin is negative or non-finite.
  void Validate() const;
};

/// A part of a surface to avoid, with the reason.
struct CollisionRegion {
  Polygon2 polygon;  ///< the region on the surface (at its height)
  RegionKind kind = RegionKind::kEdge;  ///< why it is avoided
};

/// The regions of one stair surface (landing or tread).
struct StairRegions {
  int index = 0;                     ///< the surface index in the Staircase
  double z = 0.0;                    ///< surface height [m]
  Polygon2 surface;                  ///< the whole walkable top
  Polygon2 step_region;              ///< where a foot may land; empty when none is safe
  std::vector<CollisionRegion> collision_regions;  ///< the parts of the surface to avoid
};

/// The step and collision regions of every surface of a staircase, in travel order.
class ConstrainedMap {
 public:
  ConstrainedMap() = default;
  /// The analytic map of `stairs` for a robot travelling in the stairs' direction facing `facing`.
  static ConstrainedMap FromStaircase(const Staircase& stairs, Facing facing, const ConstrainedMapSettings& settings = {});

  /// Every surface's regions, in travel order.
  const std::vector<StairRegions>& stairs() const { return stairs_; }
  /// The regions of surface `index`; throws std::out_of_range for a bad index.
  const StairRegions& stair(int index) const;
  /// Number of surfaces (the landings included).
  int size() const { return static_cast<int>(stairs_.size()); }
  /// Which way the robot faces when it travels the stairs.
  Facing facing() const { return facing_; }
  /// Up or down: the stairs' direction of travel.
  TravelDirection direction() const { return direction_; }

  /// The surface whose top contains (x, y), or -1.
  int StairAt(const Eigen::Vector2d& p) const;
  /// True when p lies in the step region of stair `index` (within tol).
  bool InStepRegion(int index, const Eigen::Vector2d& p, double tol = 1e-9) const;
  /// True when p lies in any collision region of stair `index`.
  bool InCollisionRegion(int index, const Eigen::Vector2d& p) const;
  /// The step region nearest to p (by planar distance); -1 when the map has none.
  int NearestStepRegion(const Eigen::Vector2d& p, double* distance = nullptr) const;

  /// Marks [x0, x1] (across the width) of stair `index` as a collision region of `kind` and trims
  /// the step region to the larger remaining part, so it stays convex.
  void AddCollisionBand(int index, double x0, double x1, RegionKind kind);

 private:
  std::vector<StairRegions> stairs_;
  Facing facing_ = Facing::kForward;
  TravelDirection direction_ = TravelDirection::kUp;
};

}  // namespace stairplan
