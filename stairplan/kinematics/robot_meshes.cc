#include "stairplan/kinematics/robot_meshes.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <urdf_model/model.h>

namespace stairplan {
namespace {

// No unit conversion scales by more than a thousand or less than a millionth (micrometres): a
// factor outside that is a mistake, refused before any file is looked for.
constexpr double kMaxScale = 1e3;
constexpr double kMinScale = 1e-6;

void CheckScale(const urdf::Vector3& scale, const std::string& context, const std::string& uri) {
  for (const double s : {scale.x, scale.y, scale.z}) {
    if (std::isfinite(s) && std::abs(s) <= kMaxScale && std::abs(s) >= kMinScale) continue;
    std::ostringstream message;
    message << context << ": mesh '" << uri << "': <mesh scale=\"" << scale.x << " " << scale.y << " " << scale.z
            << "\">: every factor must be finite, and between " << kMinScale << " and " << kMaxScale
            << " in size (mirroring by a negative factor is allowed)";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

const char* ToString(MeshCollision collision) {
  switch (collision) {
    case MeshCollision::kConvexHull: return "hull";
    case MeshCollision::kExactMesh: return "exact";
  }
  return "unknown";
}

MeshCollision ParseMeshCollision(const std::string& text) {
  if (text == "hull") return MeshCollision::kConvexHull;
  if (text == "exact") return MeshCollision::kExactMesh;
  throw std::invalid_argument("mesh collision: must be 'hull' or 'exact' (got '" + text + "')");
}

std::shared_ptr<const RobotMeshes> RobotMeshes::Load(const urdf::ModelInterface& model, const std::string& urdf_folder,
                                                     const MeshSettings& settings, const std::string& source) {
  auto meshes = std::make_shared<RobotMeshes>();
  meshes->collision_ = settings.collision;
  const PackagePath search =
      settings.use_ros_package_path ? settings.package_path.Then(PackagePath::FromEnvironment()) : settings.package_path;
  for (const auto& [name, link] : model.links_) {
    for (std::size_t i = 0; i < link->collision_array.size(); ++i) {
      const auto& collision = link->collision_array[i];
      if (!collision || !collision->geometry || collision->geometry->type != urdf::Geometry::MESH) continue;
      const auto& mesh = static_cast<const urdf::Mesh&>(*collision->geometry);
      const std::string context = source + ": <link name=\"" + name + "\">";
      CheckScale(mesh.scale, context, mesh.filename);
      const ResolvedUri file = ResolveMeshUri(mesh.filename, urdf_folder, search, context);
      try {
        meshes->meshes_[{name, static_cast<int>(i)}] =
            LoadMesh(file.path, Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(context + ": mesh '" + mesh.filename + "': " + e.what());
      }
    }
  }
  return meshes;
}

std::shared_ptr<const TriangleMesh> RobotMeshes::Find(const std::string& link, int index) const {
  const auto it = meshes_.find({link, index});
  return it == meshes_.end() ? nullptr : it->second;
}

}  // namespace stairplan
