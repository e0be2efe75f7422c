// The collision meshes of one robot: every <collision><mesh> of its URDF, resolved (package://,
// file://, relative paths) and read once, held by the RobotModel so that every collision model,
// validator and simulation built from it shares them.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>

#include "stairplan/kinematics/mesh_loader.h"
#include "stairplan/kinematics/package_path.h"

namespace urdf {
class ModelInterface;
}

namespace stairplan {

/// How a collision mesh becomes an FCL shape.
enum class MeshCollision {
  kConvexHull,  ///< the mesh's convex hull (fcl::Convexd): fast, conservative by the hull's excess
  kExactMesh,   ///< the triangles themselves (fcl::BVHModel<OBBRSSd>): exact, slower
};
/// "hull" or "exact".
const char* ToString(MeshCollision collision);
/// Parses "hull" or "exact"; throws std::invalid_argument otherwise.
MeshCollision ParseMeshCollision(const std::string& text);

/// Where meshes are found and how they collide.
struct MeshSettings {
  /// Searched for package:// URIs before ROS_PACKAGE_PATH.
  PackagePath package_path;
  /// Also search the folders of the ROS_PACKAGE_PATH environment variable.
  bool use_ros_package_path = true;
  MeshCollision collision = MeshCollision::kConvexHull;  ///< hull or exact triangles
};

/// The loaded collision meshes of a URDF, by link and collision element.
class RobotMeshes {
 public:
  /// Resolves and reads every collision mesh of `model`; relative paths are taken from
  /// `urdf_folder`. Throws std::invalid_argument starting with `source` and naming the link, the
  /// URI and the file (see ResolveMeshUri and LoadMesh).
  static std::shared_ptr<const RobotMeshes> Load(const urdf::ModelInterface& model, const std::string& urdf_folder,
                                                 const MeshSettings& settings, const std::string& source);

  /// The mesh of `link`'s collision element number `index` (in URDF order), null when that
  /// element is not a mesh.
  std::shared_ptr<const TriangleMesh> Find(const std::string& link, int index) const;
  /// Number of mesh collision elements (the same file used twice counts twice).
  int size() const { return static_cast<int>(meshes_.size()); }
  /// How the meshes become FCL shapes.
  MeshCollision collision() const { return collision_; }

 private:
  std::map<std::pair<std::string, int>, std::shared_ptr<const TriangleMesh>> meshes_;
  MeshCollision collision_ = MeshCollision::kConvexHull;
};

}  // namespace stairplan
