// The convex hull of a point set (a collision mesh's vertices) with qhull: what FCL's Convex
// shape needs, and a bound on how far the hull reaches beyond the mesh it wraps.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// A closed convex polytope: its vertices and outward (counter-clockwise seen from outside) triangles.
struct MeshHull {
  std::vector<Eigen::Vector3d> vertices;  ///< the hull's corners
  std::vector<std::array<int, 3>> triangles;  ///< indices into `vertices`, outward counter-clockwise
};

/// The convex hull of `points` (qhull, triangulated). Throws std::invalid_argument starting with
/// `name` when the points span no volume (fewer than four, or all in one plane or on one line).
MeshHull ComputeConvexHull(const std::vector<Eigen::Vector3d>& points, const std::string& name);

/// An upper bound on how far a point of the hull's surface can be from the mesh (`vertices`,
/// `triangles`): the largest distance to the mesh over points sampled on every hull triangle at
/// most `spacing` apart, plus `spacing` (distance to the mesh is 1-Lipschitz). A hull's clearance
/// to anything is below the mesh's by at most this much.
double HullExcess(const MeshHull& hull, const std::vector<Eigen::Vector3d>& vertices,
                  const std::vector<std::array<int, 3>>& triangles, double spacing);

}  // namespace stairplan
