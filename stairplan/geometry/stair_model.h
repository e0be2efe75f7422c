// A staircase located in the world, as the stair tracker (from a cloud) or the footfall detector
// (from footfalls) finds it: the direction in which it ascends, its levels and walking edges. It
// converts to the Staircase the planners use, in that Staircase's own frame, and back.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// A walking edge (nosing line) in the world, at the height of the level above it.
struct EdgeLine {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();  ///< the end on the right of the ascending direction
  Eigen::Vector3d b = Eigen::Vector3d::Zero();  ///< the end on the left
};

/// A staircase located in the world: the way it ascends, its levels and its walking edges.
struct StairModel {
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< unit, horizontal, the way the stairs ascend
  Eigen::Vector2d center = Eigen::Vector2d::Zero();      ///< the lowest edge's midpoint across the width [m]
  int steps = 0;       ///< risers
  double rise = 0.0;   ///< [m]
  double run = 0.0;    ///< nosing to nosing [m]
  double width = 0.0;  ///< [m]
  std::vector<double> levels;        ///< heights of the landings and treads, lowest first (steps + 1) [m]
  std::vector<double> edge_offsets;  ///< each edge's distance from `center` along `direction`, lowest first (steps) [m]
  /// How far the true nosings may be from the model's [m], in the world and relative to the
  /// model's own first edge and lowest level (the Staircase frame's origin): the fitter's bound
  /// (stairplan/geometry/stair_uncertainty.h); 0 when unknown. ToStaircase() passes it on as
  /// StairSpec::uncertainty.
  double uncertainty = 0.0;

  /// Heading of `direction` [rad].
  double yaw() const;
  /// The edges as world segments across the width, lowest first.
  std::vector<EdgeLine> Edges() const;
  /// The heading of the Staircase frame's +x for a robot travelling `travel` (up: `yaw()`).
  double TravelYaw(TravelDirection travel) const;
  /// The regular Staircase traversed `travel`, with the given nosing and landings. Throws
  /// std::invalid_argument when the model has no steps or its numbers are out of StairSpec's range.
  Staircase ToStaircase(TravelDirection travel, double nosing = 0.0, double landing = 1.2) const;
  ///@{
  /// A point of ToStaircase(travel, nosing)'s frame in the world, and back.
  Eigen::Vector3d StairToWorld(const Eigen::Vector3d& p_S, TravelDirection travel, double nosing = 0.0) const;
  Eigen::Vector3d WorldToStair(const Eigen::Vector3d& p_W, TravelDirection travel, double nosing = 0.0) const;
  ///@}
};

/// The model of `stairs` placed in the world: p_W = origin_W + Rz(yaw) p_S (e.g. the ground truth
/// of a synthetic scene). Per-step rises and runs are averaged into `rise` and `run`.
StairModel ModelOfStaircase(const Staircase& stairs, const Eigen::Vector3d& origin_W, double yaw);

}  // namespace stairplan
