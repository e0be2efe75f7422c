#include "stairplan/collision/mesh_shape.h"

#include <map>
#include <mutex>
#include <utility>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/math/bv/OBBRSS.h>

#include "stairplan/collision/convex_hull.h"

namespace stairplan {
namespace {

std::shared_ptr<const fcl::CollisionGeometryd> MakeConvex(const MeshHull& hull, const Eigen::Vector3d& centre) {
  auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (const Eigen::Vector3d& v : hull.vertices) vertices->push_back(v - centre);
  auto faces = std::make_shared<std::vector<int>>();
  for (const auto& t : hull.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  auto convex = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles.size()), faces);
  convex->computeLocalAABB();
  return convex;
}

std::shared_ptr<const fcl::CollisionGeometryd> MakeBvh(const TriangleMesh& mesh, const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) vertices.push_back(v - centre);
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2]));
  }
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

MeshShape BuildShape(const TriangleMesh& mesh, MeshCollision collision) {
  MeshShape shape;
  const Eigen::Vector3d lo = mesh.Min(), hi = mesh.Max();
  shape.centre = 0.5 * (lo + hi);
  shape.size = hi - lo;
  const MeshHull hull = ComputeConvexHull(mesh.vertices, mesh.file);
  for (const Eigen::Vector3d& v : hull.vertices) {
    shape.hull_vertices.push_back(v - shape.centre);
    shape.bounding_radius = std::max(shape.bounding_radius, (v - shape.centre).norm());
  }
  shape.hull_triangles = static_cast<int>(hull.triangles.size());
  shape.geometry = collision == MeshCollision::kConvexHull ? MakeConvex(hull, shape.centre) : MakeBvh(mesh, shape.centre);
  return shape;
}

// Each entry keeps its mesh alive, so no other mesh can take its address while it is cached.
struct CacheEntry {
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const MeshShape> shape;
};

}  // namespace

std::shared_ptr<const MeshShape> GetMeshShape(const std::shared_ptr<const TriangleMesh>& mesh, MeshCollision collision) {
  static std::mutex mutex;
  static std::map<std::pair<const TriangleMesh*, MeshCollision>, CacheEntry> cache;
  std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(mesh.get(), collision);
  const auto hit = cache.find(key);
  if (hit != cache.end()) return hit->second.shape;
  auto shape = std::make_shared<const MeshShape>(BuildShape(*mesh, collision));
  cache.emplace(key, CacheEntry{mesh, shape});
  return shape;
}

}  // namespace stairplan
