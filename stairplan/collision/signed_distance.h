// Signed distance between two convex FCL primitives, with the narrow-phase solver chosen for
// correctness: FCL 0.7's default libccd GJK gets some box-box distances wrong (fcl#508), so
// separated pairs use FCL's own GJK (GST_INDEP). A box, cylinder or sphere penetrating a stair box
// gets its depth from separating axes (exact for box-box and sphere-box, and allocation-free);
// other penetrating pairs from FCL's contact computation. When FCL throws or returns nonsense,
// which happens on deep penetration, a conservative bound is returned and flagged.
#pragma once

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include "stairplan/geometry/shapes.h"

namespace stairplan {

/// Result of one signed-distance query. Points are in the world frame.
struct SignedDistanceResult {
  double distance = 0.0;  ///< > 0 apart, < 0 penetrating (minus the penetration depth) [m]
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  ///< closest (or deepest) point on a
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  ///< closest (or deepest) point on b
  bool fallback = false;  ///< FCL failed; distance is a lower bound from bounding volumes
};

/// What the caller knows about the shapes, for the fallback: the radius of a sphere about a's
/// centre enclosing a, and either b's enclosing radius or, for stair solids, b as an axis-aligned box.
struct SignedDistanceHints {
  double bounding_radius_a = 0.0;  ///< radius about a's centre enclosing a [m]
  double bounding_radius_b = 0.0;  ///< radius about b's centre enclosing b [m]; unused when `box_b` is set
  const Box3* box_b = nullptr;  ///< b as a stair solid's axis-aligned box, or null
};

/// Signed distance between a at pose_a and b at pose_b (both convex primitives).
SignedDistanceResult SignedDistance(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a,
                                    const fcl::CollisionGeometryd& b, const Eigen::Isometry3d& pose_b,
                                    const SignedDistanceHints& hints = {});

}  // namespace stairplan
