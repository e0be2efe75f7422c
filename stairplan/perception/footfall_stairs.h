// Identifying stairs from footfalls (PCT/US2021/022953 ("Identifying stairs from footfalls")):
// pairs of footfalls whose height and horizontal separation look like a step from one tread to the
// next, with no footfall between them and the most adjacent pairs first; pairs linked by shared
// footfalls and a common direction form one staircase; its footfalls clustered by height are its
// treads (each at its cluster's mean height), and its edges pass through the midpoint of the
// closest footfalls of adjacent clusters, perpendicular to the direction through the clusters'
// centroids. A path may hold several.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stairplan/perception/footfall.h"
#include "stairplan/geometry/stair_model.h"
#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// Thresholds and tolerances of StairsFromFootfalls().
struct FootfallStairsSettings {
  double min_rise = 0.08;   ///< stair height threshold, lower end [m] (PCT/US2021/022953 [0050])
  double max_rise = 0.30;   ///< stair height threshold, upper end [m] (PCT/US2021/022953 [0051])
  double min_depth = 0.12;  ///< stair depth threshold, lower end: horizontal separation [m]
  double max_depth = 0.60;  ///< stair depth threshold, upper end [m]
  /// Another footfall within this band around the segment between a pair intervenes
  /// (PCT/US2021/022953 [0052]) [m].
  double corridor = 0.30;
  /// Footfalls sorted by height start a new cluster across a gap larger than this [m].
  double height_tolerance = 0.04;
  /// Pairs sharing a footfall belong to the same staircase when their directions agree this well [rad].
  double direction_tolerance = 0.6;
  int min_risers = 2;         ///< fewer are not reported as stairs
  int min_cluster_footfalls = 2;  ///< a smaller cluster is a stray footfall: it joins its nearest neighbour
  double width_margin = 0.15; ///< added to the footfalls' spread across on each side for the width [m]

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// A walking edge found from footfalls: a line through `midpoint`, along `along`.
struct FootfallEdge {
  Eigen::Vector3d midpoint = Eigen::Vector3d::Zero();  ///< between the closest footfalls, at the upper tread's height
  Eigen::Vector2d along = Eigen::Vector2d::UnitY();    ///< unit, perpendicular to the stairs' direction
};

/// One staircase found from footfalls.
struct FootfallStaircase {
  StairModel model;                   ///< regular fit: rise and run by least squares over treads and edges
  TravelDirection traversal = TravelDirection::kUp;  ///< how the robot walked it
  std::vector<double> tread_heights;  ///< each cluster's mean height, lowest first (landings included)
  std::vector<int> cluster_sizes;     ///< footfalls per cluster
  std::vector<Eigen::Vector3d> centroids;  ///< per cluster
  std::vector<FootfallEdge> edges;    ///< through the closest-footfall midpoints, lowest first
  double t_begin = 0.0;               ///< first footfall on it [s]
  double t_end = 0.0;                 ///< last footfall on it [s]
  std::vector<int> footfalls;         ///< indices of the footfalls it was built from
};

/// The staircases along the footfalls' path, in the order they were walked. Throws
/// std::invalid_argument naming the footfall for a non-finite position.
std::vector<FootfallStaircase> StairsFromFootfalls(const std::vector<Footfall>& footfalls, const FootfallStairsSettings& settings = {});

}  // namespace stairplan
