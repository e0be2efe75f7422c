// A collision shape (box, cylinder, sphere, or a mesh as its hull or its triangles) fixed to a
// robot frame: a leg chain's link frame or the base. Built from the URDF's <collision> elements.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include "stairplan/collision/mesh_shape.h"
#include "stairplan/kinematics/robot_model.h"

namespace urdf {
class Link;
}

namespace stairplan {

/// The kind of a collision shape.
enum class ShapeType { kBox, kCylinder, kSphere, kMesh };

/// One collision shape of the robot.
struct CollisionShape {
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;  ///< the FCL shape, centred at `local`
  ShapeType type = ShapeType::kBox;  ///< box, cylinder, sphere or mesh
  /// Box sides; cylinder (r, r, length); sphere (r, r, r); a mesh's bounding box sides [m].
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  /// Shape pose in its frame (for a mesh: the centre of its bounding box, where its geometry sits).
  Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
  std::shared_ptr<const MeshShape> mesh;  ///< the mesh's shape for kMesh, null otherwise
  std::string link;           ///< the URDF link it belongs to
  int segment = -1;           ///< leg chain segment whose tip frame carries it; -1: the base frame
  /// The foot's contact sphere, or the foot link's mesh of a mesh foot: touches the ground by design.
  bool foot_contact = false;
  /// For a mesh foot's contact shape: the centre of its contact sphere (LegModel::foot_sphere_center)
  /// in the shape's frame (`local`); the foot meets the surface it stands on contact_radius below it.
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
  double contact_radius = 0.0;  ///< LegModel::foot_radius of a mesh foot's contact shape [m]
  /// Part of the foot: on the foot link or on a link fixed between the knee's link and the foot
  /// (the foot sphere, ANYmal B's adapter tube, ANYmal C's shank tube on its FOOT link). The knee's
  /// own link (stairbot's shank, a Unitree calf) is not, though it too is rigid with the foot.
  bool foot_part = false;
  double bounding_radius = 0.0;  ///< radius of a sphere about the shape's centre enclosing it [m]
};

/// The shapes of one URDF link of `robot`, posed in that link's frame (segment -1, to be set by
/// the caller); meshes come from robot.meshes() as robot.meshes().collision() says. Throws
/// std::invalid_argument naming the robot's source, the link and the mesh file for a mesh that
/// spans no volume.
std::vector<CollisionShape> LinkCollisionShapes(const urdf::Link& link, const RobotModel& robot);

/// The height of the shape's lowest point when posed at `pose_W` (exact for boxes, cylinders,
/// spheres and hulls; for an exact mesh its hull's, which is the same point) [m].
double LowestZ(const CollisionShape& shape, const Eigen::Isometry3d& pose_W);

/// An FCL box with the given side lengths.
std::shared_ptr<const fcl::CollisionGeometryd> MakeFclBox(const Eigen::Vector3d& size);

}  // namespace stairplan
