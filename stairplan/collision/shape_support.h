// Support functions of the collision shapes (how far a shape reaches along a direction) and the
// cheap lower bounds on clearances built from them. A clearance query measures with FCL only the
// shape pairs these bounds cannot rule out, closest first; a pair ruled out is surely no closer
// than one measured, so the clearance is the one every pair would give.
#pragma once

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include "stairplan/geometry/shapes.h"

namespace stairplan {

/// The vertex of a mesh shape (hull or triangles) furthest along `n_local`, in its own frame; null
/// for other shapes. A mesh's support is its hull's, so the triangles' vertices serve as well.
const Eigen::Vector3d* MeshSupportVertex(const fcl::CollisionGeometryd& g, const Eigen::Vector3d& n_local);

/// True for a mesh shape: an fcl::Convexd hull or an OBBRSS triangle model.
bool IsMeshGeometry(const fcl::CollisionGeometryd& g);

/// How far `g`, turned by `rotation`, reaches from its origin along unit direction `n` (a
/// primitive's half-extent; a mesh, not centred on its origin, may reach less one way than the
/// other), or NaN for a geometry we do not model.
double SupportAlong(const fcl::CollisionGeometryd& g, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& n);

/// A lower bound on the distance between a (at pose_a, inside a sphere of radius_a about its
/// origin) and b: the gap between their extents along the line joining their origins when they
/// are apart along it, else the bounding spheres' gap (negative when they may overlap).
double SeparationLowerBound(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, double radius_a,
                            const fcl::CollisionGeometryd& b, const Eigen::Isometry3d& pose_b, double radius_b);

/// A lower bound on the signed distance from a (as above) to the axis-aligned `box`: the gap
/// along the direction from the box's point nearest a's origin when positive, else the bounding
/// sphere's gap.
double BoxSeparationLowerBound(const fcl::CollisionGeometryd& a, const Eigen::Isometry3d& pose_a, double radius_a,
                               const Box3& box);

}  // namespace stairplan
