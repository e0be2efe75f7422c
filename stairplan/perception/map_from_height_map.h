// A ConstrainedMap from data (US 2020/0324412 A1 ("Robotically negotiating stairs") [0043]-[0048],
// claim 1): the stairs the tracker fitted give each stair's surface and its step region; the height
// map then adds what the data says: height discontinuities become edge and riser collision regions
// (dilated for the nosing and the cell size), poorly seen cells and cells off their surface become
// data collision regions, and each step region is trimmed so it stays convex. The map is in the
// fitted Staircase's frame.
#pragma once

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/perception/height_map.h"
#include "stairplan/geometry/stair_model.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// How ConstrainedMapFromHeightMap() turns the height map's data into collision regions.
struct MapFromHeightMapSettings {
  TravelDirection travel = TravelDirection::kUp;  ///< which way the robot will traverse the stairs
  Facing facing = Facing::kForward;               ///< and facing which way (US 2020/0324412 [0047])
  ConstrainedMapSettings margins;                 ///< the analytic margins
  double nosing = 0.0;          ///< nosing assumed in the Staircase (the data shows walking edges) [m]
  double jump = 0.05;           ///< a height step between neighbouring cells above this is an edge [m]
  /// Edge cells grow by half a cell, and towards the lower side by this more (a nosing's depth) [m].
  double edge_dilation = 0.02;
  double surface_tolerance = 0.04;  ///< a cell further than this off its surface's height is an obstacle [m]
  /// Shortest landing put before and after the flight [m]: the robot stands on the landing it
  /// looks from, and a planner needs room there even where the sensor saw little of it.
  double min_landing = 1.2;
  double max_landing = 3.0;     ///< longest landing [m]

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// The fitted stairs as a Staircase and their constrained map from data.
struct PerceivedStairs {
  Staircase stairs;         ///< in its own frame: model.StairToWorld(p, travel, nosing) places it
  ConstrainedMap map;       ///< in the same frame
  int edge_bands = 0;       ///< collision bands added for data edges inside step regions
  int data_bands = 0;       ///< collision bands added for poor, unknown-in-region or off-surface data
};

/// Builds the constrained map of `model` refined by `map` (filled or not). Landings extend as far
/// as the data does (within the settings' limits). Throws std::invalid_argument for a model
/// without steps.
PerceivedStairs ConstrainedMapFromHeightMap(const HeightMap& map, const StairModel& model, const MapFromHeightMapSettings& settings = {});

}  // namespace stairplan
