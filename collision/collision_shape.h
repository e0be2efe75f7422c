// A primitive collision shape (box, cylinder, sphere) fixed to a robot frame: a leg chain's link
// frame or the base. Built from the URDF's <collision> elements; meshes are refused.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

namespace urdf {
class Link;
}

namespace stairplan {

enum class ShapeType { kBox, kCylinder, kSphere };

/// One collision primitive of the robot.
struct CollisionShape {
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;
  ShapeType type = ShapeType::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box sides; cylinder (r, r, length); sphere (r, r, r) [m]
  Eigen::Isometry3d local = Eigen::Isometry3d::Identity();  ///< shape pose in its frame
  std::string link;           ///< the URDF link it belongs to
  int segment = -1;           ///< leg chain segment whose tip frame carries it; -1: the base frame
  bool foot_contact = false;  ///< the foot's contact sphere (touches the ground by design)
  /// Part of the foot: on the foot link or on a link fixed between the knee's link and the foot
  /// (the foot sphere, ANYmal B's adapter tube, ANYmal C's shank tube on its FOOT link). The knee's
  /// own link (stairbot's shank, a Unitree calf) is not, though it too is rigid with the foot.
  bool foot_part = false;
  double bounding_radius = 0.0;  ///< radius of a sphere about the shape's centre enclosing it [m]
};

/// The primitives of one URDF link, posed in that link's frame (segment -1, to be set by the
/// caller). Throws std::invalid_argument naming `source` and the link for a mesh collision.
std::vector<CollisionShape> LinkCollisionShapes(const urdf::Link& link, const std::string& source);

/// The height of the shape's lowest point when posed at `pose_W` (exact for boxes, cylinders and
/// spheres) [m].
double LowestZ(const CollisionShape& shape, const Eigen::Isometry3d& pose_W);

/// An FCL box with the given side lengths.
std::shared_ptr<const fcl::CollisionGeometryd> MakeFclBox(const Eigen::Vector3d& size);

}  // namespace stairplan
