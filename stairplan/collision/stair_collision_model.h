// The stairs as FCL solids: one block under every surface (its top is the tread or landing, its
// front face the riser) and one lip per nosing, from Staircase::Solids().
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include "stairplan/geometry/staircase.h"

namespace stairplan {

/// Which part of a stair a point lies on, for reports and collision regions.
enum class StairPart { kTread, kRiser, kNosing, kOther };
/// Returns "tread", "riser", "nosing" or "other".
const char* ToString(StairPart part);

/// One solid: the geometry box, its FCL box centred at `pose`.
struct StairSolid {
  Box3 box;  ///< the solid in the world frame
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;  ///< its FCL box, centred at `pose`
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< the box's centre in the world frame
};

/// Const model of the stairs for clearance queries.
class StairCollisionModel {
 public:
  /// One solid per box of `stairs`.Solids() (blocks and nosing lips).
  explicit StairCollisionModel(const Staircase& stairs);

  /// Every solid of the stairs.
  const std::vector<StairSolid>& solids() const { return solids_; }
  /// The part of solid `index` nearest to `point_W` (on or inside it): nosing lips are kNosing; on
  /// a block, the top face is kTread, the vertical faces across x are kRiser, the rest kOther.
  StairPart PartAt(int index, const Eigen::Vector3d& point_W, double tol = 1e-6) const;

 private:
  std::vector<StairSolid> solids_;
};

}  // namespace stairplan
