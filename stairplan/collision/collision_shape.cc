#include "stairplan/collision/collision_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <urdf_model/link.h>

#include "stairplan/kinematics/urdf_pose.h"

namespace stairplan {
std::shared_ptr<const fcl::CollisionGeometryd> MakeFclBox(const Eigen::Vector3d& size) {
  auto box = std::make_shared<fcl::Boxd>(size);
  box->computeLocalAABB();
  return box;
}

double LowestZ(const CollisionShape& shape, const Eigen::Isometry3d& pose_W) {
  const double centre_z = pose_W.translation().z();
  const Eigen::Matrix3d& R = pose_W.linear();
  switch (shape.type) {
    case ShapeType::kBox:  // the corner whose every half-side points down
      return centre_z - 0.5 * (R.row(2).cwiseAbs().dot(shape.size));
    case ShapeType::kCylinder: {  // the lower cap's rim, on the side the axis tilts away from
      const double axis_z = std::abs(R(2, 2));
      return centre_z - 0.5 * shape.size.z() * axis_z - shape.size.x() * std::sqrt(std::max(0.0, 1.0 - axis_z * axis_z));
    }
    case ShapeType::kSphere:
      return centre_z - shape.size.x();
    case ShapeType::kMesh: {
      double lowest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& v : shape.mesh->hull_vertices) lowest = std::min(lowest, R.row(2).dot(v));
      return centre_z + lowest;
    }
  }
  return centre_z;
}

std::vector<CollisionShape> LinkCollisionShapes(const urdf::Link& link, const RobotModel& robot) {
  std::vector<CollisionShape> shapes;
  for (std::size_t index = 0; index < link.collision_array.size(); ++index) {
    const auto& collision = link.collision_array[index];
    if (!collision || !collision->geometry) continue;
    CollisionShape shape;
    shape.link = link.name;
    shape.local = UrdfPoseToIsometry(collision->origin);
    switch (collision->geometry->type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(*collision->geometry);
        shape.type = ShapeType::kBox;
        shape.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
        shape.geometry = MakeFclBox(shape.size);
        shape.bounding_radius = 0.5 * shape.size.norm();
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision->geometry);
        shape.type = ShapeType::kCylinder;
        shape.size = Eigen::Vector3d(cylinder.radius, cylinder.radius, cylinder.length);
        auto geometry = std::make_shared<fcl::Cylinderd>(cylinder.radius, cylinder.length);
        geometry->computeLocalAABB();
        shape.geometry = geometry;
        shape.bounding_radius = std::hypot(cylinder.radius, 0.5 * cylinder.length);
        break;
      }
      case urdf::Geometry::SPHERE: {
        const auto& sphere = static_cast<const urdf::Sphere&>(*collision->geometry);
        shape.type = ShapeType::kSphere;
        shape.size = Eigen::Vector3d::Constant(sphere.radius);
        auto geometry = std::make_shared<fcl::Sphered>(sphere.radius);
        geometry->computeLocalAABB();
        shape.geometry = geometry;
        shape.bounding_radius = sphere.radius;
        break;
      }
      case urdf::Geometry::MESH: {
        const std::shared_ptr<const TriangleMesh> loaded = robot.meshes().Find(link.name, static_cast<int>(index));
        if (!loaded) throw std::invalid_argument(robot.source() + ": <link name=\"" + link.name + "\">: mesh not loaded");
        try {
          shape.mesh = GetMeshShape(loaded, robot.meshes().collision());
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(robot.source() + ": <link name=\"" + link.name + "\">: " + e.what());
        }
        shape.type = ShapeType::kMesh;
        shape.geometry = shape.mesh->geometry;
        shape.size = shape.mesh->size;
        shape.bounding_radius = shape.mesh->bounding_radius;
        shape.local = shape.local * Eigen::Translation3d(shape.mesh->centre);
        break;
      }
      default:
        throw std::invalid_argument(robot.source() + ": <link name=\"" + link.name + "\">: unknown <collision> geometry");
    }
    shapes.push_back(std::move(shape));
  }
  return shapes;
}

}  // namespace stairplan
