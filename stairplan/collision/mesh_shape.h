// A collision mesh as an FCL shape: by default its convex hull (fcl::Convexd), or the triangles
// themselves (fcl::BVHModel<OBBRSSd>). Built once per mesh and process, whoever asks (every
// RobotCollisionModel of a sweep shares them), and expressed about the centre of the mesh's
// bounding box so that bounding-sphere pruning stays tight for meshes far from their link origin.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/collision_geometry.h>

#include "stairplan/kinematics/robot_meshes.h"

namespace stairplan {

/// One mesh's FCL shape and what the clearance queries need of it.
struct MeshShape {
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;  ///< vertices relative to `centre`
  /// Centre of the mesh's bounding box in the mesh's own frame; the geometry sits there.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  /// The hull's vertices relative to `centre` (also for the exact mesh: its support points).
  std::vector<Eigen::Vector3d> hull_vertices;
  int hull_triangles = 0;  ///< how many triangles the hull has
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< bounding box sides [m]
  double bounding_radius = 0.0;  ///< of a sphere about `centre` enclosing the mesh [m]
};

/// The shape of `mesh` as `collision` says, from the process-wide cache. Throws
/// std::invalid_argument naming the mesh's file when it spans no volume (a hull needs one).
std::shared_ptr<const MeshShape> GetMeshShape(const std::shared_ptr<const TriangleMesh>& mesh, MeshCollision collision);

}  // namespace stairplan
