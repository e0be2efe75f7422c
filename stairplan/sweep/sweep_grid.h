// The grid of a parameter sweep over stair geometries: axes written "A:B:N", the points in a fixed
// order (so any shard or thread count yields the same rows), and sharding for batch systems.
#pragma once

#include <string>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// N evenly spaced values from lo to hi inclusive (N = 1: just lo).
struct SweepAxis {
  double lo = 0.0;  ///< first value
  double hi = 0.0;  ///< last value
  int count = 1;  ///< number of values

  /// The values, lo first.
  std::vector<double> Values() const;
  /// Parses "A:B:N" or a single value "V"; throws FieldError naming `flag`.
  static SweepAxis Parse(const std::string& text, const std::string& flag);
};

/// Everything a sweep varies and holds fixed.
struct SweepGrid {
  SweepAxis rise{0.10, 0.25, 20};  ///< riser heights [m]
  SweepAxis run{0.20, 0.35, 20};  ///< tread runs [m]
  SweepAxis nosing{0.02, 0.02, 1};  ///< nosings [m]
  SweepAxis steps{7, 7, 1};  ///< whole numbers
  std::vector<TravelDirection> directions{TravelDirection::kUp};  ///< directions of travel
  Facing facing = Facing::kForward;  ///< which way the body faces
};

/// One grid point: a staircase to plan and validate.
struct SweepPoint {
  int index = 0;  ///< position in EnumeratePoints() order
  TravelDirection direction = TravelDirection::kUp;  ///< up or down
  int steps = 7;  ///< number of risers
  double nosing = 0.02;  ///< nosing [m]
  double rise = 0.17;  ///< riser height [m]
  double run = 0.27;  ///< tread run [m]

  /// The point's staircase: StairSpec's defaults with this point's steps, rise, run, nosing, direction.
  StairSpec Spec() const;
};

/// Every point, in the fixed order direction > steps > nosing > rise > run.
std::vector<SweepPoint> EnumeratePoints(const SweepGrid& grid);

/// `indices` (into `points`) in the order to hand them to workers: the points expected to take
/// longest first (more steps, then higher risers, then longer runs), so that no worker is left
/// with a slow point while the others idle at the end. A plan's cost grows with its steps and
/// with the rise (posture search and retries), and EnumeratePoints puts those points last.
/// Only the order of computing changes: results are stored by index.
std::vector<int> SlowestFirst(std::vector<int> indices, const std::vector<SweepPoint>& points);

/// Which part of a sweep this process computes: points with index % count == index.
struct Shard {
  int index = 0;  ///< this shard, 0 .. count - 1
  int count = 1;  ///< number of shards
  /// Parses "i/N"; throws FieldError naming `flag`.
  static Shard Parse(const std::string& text, const std::string& flag);
  /// True when point `point_index` belongs to this shard.
  bool Holds(int point_index) const { return point_index % count == index; }
};

/// Parses "up", "down" or "up,down"; throws FieldError naming `flag`.
std::vector<TravelDirection> ParseDirections(const std::string& text, const std::string& flag);

}  // namespace stairplan
