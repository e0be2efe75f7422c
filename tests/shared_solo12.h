// Solo 12 from ../shared/data/robots/solo12, its meshes found through the folder as a package
// path (not ROS_PACKAGE_PATH): for tests that plan or measure with it.
#pragma once

#include <optional>
#include <string>

#include "stairplan/kinematics/robot_meshes.h"
#include "stairplan/kinematics/robot_model.h"
#include "test_paths.h"

namespace stairplan::testing {

/// The mesh settings that load Solo 12 from `folder` with `collision` meshes.
inline MeshSettings Solo12Meshes(const std::string& folder, MeshCollision collision = MeshCollision::kConvexHull) {
  MeshSettings meshes;
  meshes.package_path = PackagePath::FromString(folder);
  meshes.use_ros_package_path = false;
  meshes.collision = collision;
  return meshes;
}

/// Solo 12, or nothing when ../shared is absent (the caller WARNs and skips).
inline std::optional<RobotModel> SharedSolo12() {
  const std::string folder = SharedPath("data/robots/solo12");
  if (folder.empty()) return std::nullopt;
  return RobotModel::FromUrdfFile(folder + "/solo12.urdf", {}, Solo12Meshes(folder));
}

}  // namespace stairplan::testing
