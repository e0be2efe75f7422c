// The shape of a sweep's success region over rise x run, so that a user need not read 400 rows
// to know it: whether the valid points form one connected area, and which failures break
// "steeper stairs fail first" (validity monotone in steepness: if (rise, run) is valid, so is
// every point with a lower-or-equal rise and a longer-or-equal run).
#pragma once

#include <string>
#include <vector>

#include "stairplan/sweep/sweep_runner.h"

namespace stairplan {

/// A point that is not valid although a steeper one is.
struct SteepnessBreak {
  SweepRow failed;  ///< the invalid point's row
  /// The nearest valid point (fewest grid steps) with a higher-or-equal rise and a
  /// shorter-or-equal run than `failed`.
  SweepPoint steeper_valid;
};

/// The success region of one rise x run slice of a sweep (one direction, step count and nosing).
struct SweepRegion {
  TravelDirection direction = TravelDirection::kUp;  ///< the slice's direction
  int steps = 0;  ///< the slice's number of risers
  double nosing = 0.0;  ///< the slice's nosing [m]
  int points = 0;  ///< grid points in the slice
  int valid = 0;  ///< of which valid
  /// Connected areas of valid points, neighbours being adjacent rise or run values of the slice
  /// (not diagonals).
  int areas = 0;
  std::vector<SteepnessBreak> breaks;  ///< in point order

  /// True when the valid points form at most one area.
  bool Connected() const { return areas <= 1; }
  /// True when no invalid point has a valid steeper one (failures start where the stairs get steeper).
  bool SteeperFailFirst() const { return breaks.empty(); }
};

/// One region per slice of `rows`, in the order the slices first appear. The grid is the rise and
/// run values the rows hold, so give it a whole sweep (merged shards), not one shard.
std::vector<SweepRegion> AnalyseSweepRegions(const std::vector<SweepRow>& rows);

/// The regions as lines of text, every break listed with its status and reason.
std::string SweepRegionsToText(const std::vector<SweepRegion>& regions);

}  // namespace stairplan
