// Filling the holes of a HeightMap the way US 2020/0324412 A1 ("Robotically negotiating stairs")
// [0042] describes: a hole between a near, high surface and a far, low one (a near-far contrast) is
// an occlusion and is filled flat at the low surface's height (the tread hidden behind a nosing or
// seen only from below); a hole without contrast is poor vision and is filled smoothly. Holes too
// wide to bridge stay unknown.
#pragma once

#include "stairplan/perception/height_map.h"

namespace stairplan {

/// How FillGaps() tells occlusions from poor vision, and how far it bridges.
struct GapFillSettings {
  /// A height difference across a hole above this is a near-far contrast (an occlusion) [m].
  double contrast = 0.05;
  /// Holes are bridged only between measured cells at most this far apart [m].
  double max_gap = 1.0;
  /// Smoothly filled cells whose nearest bridge is longer than this are marked kPoor [m].
  double poor_span = 0.2;
  /// Relaxation sweeps that smooth the filled values (a discrete Laplace equation).
  int smoothing_sweeps = 30;

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// What FillGaps() did, in cells.
struct GapFillReport {
  int occluded = 0;  ///< cells filled flat
  int smoothed = 0;  ///< cells filled smoothly (kPoor ones included)
  int poor = 0;      ///< smoothly filled cells far from data
  int unknown = 0;   ///< cells left unknown
};

/// Fills the kUnknown cells of `map` in place; measured cells are never changed.
GapFillReport FillGaps(HeightMap& map, const GapFillSettings& settings = {});

}  // namespace stairplan
