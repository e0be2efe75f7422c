#include "stairplan/kinematics/mesh_loader.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Geometry>

#include "stairplan/kinematics/collada_check.h"

namespace stairplan {
namespace {

namespace fs = std::filesystem;

enum class MeshFormat { kStl, kObj, kCollada };

std::atomic<std::size_t> files_read{0};

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

MeshFormat FormatOf(const std::string& path) {
  const std::string extension = Lower(fs::path(path).extension().string());
  if (extension == ".stl") return MeshFormat::kStl;
  if (extension == ".obj") return MeshFormat::kObj;
  if (extension == ".dae") return MeshFormat::kCollada;
  throw std::invalid_argument(path + ": unsupported mesh format '" + extension + "' (STL, OBJ or COLLADA .dae)");
}

std::string Format(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << v.x() << " " << v.y() << " " << v.z();
  return out.str();
}

void CheckScale(const std::string& path, const Eigen::Vector3d& scale) {
  if (!scale.allFinite() || (scale.array() == 0.0).any()) {
    throw std::invalid_argument(path + ": <mesh scale=\"" + Format(scale) + "\">: every scale factor must be finite and non-zero");
  }
}

// Assimp turns every scene into its own y-up convention: COLLADA files are rotated from their
// <up_axis> to y up (and scaled by <unit meter>), STL and OBJ are left as they are. URDF frames are
// z up, so a COLLADA scene is turned back from y up to z up (a Z_UP file comes out unchanged).
Eigen::Matrix3d ToUrdfFrame(MeshFormat format) {
  if (format != MeshFormat::kCollada) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

Eigen::Matrix4d ToEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

// Appends the triangles of `node` and its children, posed by their transforms, to `mesh`.
void Collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, TriangleMesh& mesh) {
  const Eigen::Matrix4d pose = parent * ToEigen(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& part = *scene.mMeshes[node.mMeshes[i]];
    if (!(part.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int offset = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
      const aiVector3D& p = part.mVertices[v];
      mesh.vertices.push_back((pose * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>());
    }
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines are not surfaces
      mesh.triangles.push_back({offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) Collect(scene, *node.mChildren[c], pose, mesh);
}

// Assimp reads a binary STL whose header starts with "solid" (Solo's do) as ASCII, and a cut-off
// file then fails with a message about primitive types, or not at all when the cut falls between
// facets. A binary STL's size is fixed by its triangle count, so check it first.
void CheckStlSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(84, '\0');
  in.read(head.data(), 84);
  const std::streamsize got = in.gcount();
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw std::invalid_argument(path + ": cannot read the mesh file");
  const std::size_t first = head.find_first_not_of(" \t\r\n");
  const bool ascii_start = first != std::string::npos && head.compare(first, 5, "solid") == 0;
  if (got == 84) {
    const auto* count_bytes = reinterpret_cast<const unsigned char*>(head.data() + 80);
    const std::uintmax_t count = count_bytes[0] | (count_bytes[1] << 8) | (count_bytes[2] << 16) |
                                 (static_cast<std::uintmax_t>(count_bytes[3]) << 24);
    if (84 + 50 * count == size) return;  // a complete binary STL
    if (!ascii_start) {
      throw std::invalid_argument(path + ": truncated or corrupt binary STL: its header counts " + std::to_string(count) +
                                  " triangles (" + std::to_string(84 + 50 * count) + " bytes), the file has " +
                                  std::to_string(size) + " bytes");
    }
  }
  if (!ascii_start) throw std::invalid_argument(path + ": not an STL file (" + std::to_string(size) + " bytes)");
  // ASCII: it must end with "endsolid".
  std::ifstream text(path, std::ios::binary);
  std::stringstream buffer;
  buffer << text.rdbuf();
  if (buffer.str().find("endsolid") == std::string::npos) {
    throw std::invalid_argument(path + ": truncated STL: no 'endsolid', and its size (" + std::to_string(size) +
                                " bytes) does not match the triangle count of a binary STL");
  }
}

// An OBJ has triangles only with three vertex lines and a face line, so one without is refused here.
// Assimp 5.2.5's OBJ reader also needs it: it copies each line into a buffer the size of the file and
// parses face indices with atoi, which expects a terminating NUL. Only a file that is one line leaves
// no zero byte after it (ASan's strict string check caught atoi reading past the buffer in a 21-byte
// file found by fuzz_mesh); with several lines, the shorter ones leave zeros behind the longest.
void CheckObjHasFaces(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  int vertices = 0;
  int faces = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    vertices += keyword == "v";
    faces += keyword == "f";
  }
  if (vertices < 3 || faces == 0) {
    throw std::invalid_argument(path + ": the mesh has no triangles (an OBJ needs three 'v' lines and an 'f' line; " +
                                "it has " + std::to_string(vertices) + " and " + std::to_string(faces) + ")");
  }
}

// Merges vertices at the same position (STL repeats a vertex for every triangle using it) and
// drops triangles without area.
void Weld(TriangleMesh& mesh) {
  std::map<std::array<double, 3>, int> index;
  std::vector<Eigen::Vector3d> welded;
  std::vector<int> remap(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    const auto [it, added] = index.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, static_cast<int>(welded.size()));
    if (added) welded.push_back(v);
    remap[i] = it->second;
  }
  std::vector<std::array<int, 3>> triangles;
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> r = {remap[static_cast<std::size_t>(t[0])], remap[static_cast<std::size_t>(t[1])],
                                  remap[static_cast<std::size_t>(t[2])]};
    const Eigen::Vector3d& a = welded[static_cast<std::size_t>(r[0])];
    const double area2 = (welded[static_cast<std::size_t>(r[1])] - a).cross(welded[static_cast<std::size_t>(r[2])] - a).norm();
    if (area2 > 0.0) triangles.push_back(r);
  }
  // Keep only the vertices some triangle uses (a stray point must not widen the hull).
  std::vector<int> used(welded.size(), -1);
  mesh.vertices.clear();
  for (auto& t : triangles) {
    for (int& k : t) {
      int& slot = used[static_cast<std::size_t>(k)];
      if (slot < 0) {
        slot = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(welded[static_cast<std::size_t>(k)]);
      }
      k = slot;
    }
  }
  mesh.triangles = std::move(triangles);
}

TriangleMesh ReadMesh(const std::string& path, const Eigen::Vector3d& scale) {
  const MeshFormat format = FormatOf(path);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw std::invalid_argument(path + ": no such mesh file");
  if (format == MeshFormat::kStl) CheckStlSize(path);
  if (format == MeshFormat::kObj) CheckObjHasFaces(path);
  if (format == MeshFormat::kCollada) CheckColladaFile(path);
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  ++files_read;
  if (scene == nullptr) {
    throw std::invalid_argument(path + ": not a readable mesh: " + std::string(importer.GetErrorString()));
  }
  TriangleMesh mesh;
  mesh.file = path;
  // An incomplete scene is assimp's placeholder for a file without geometry.
  if (scene->mRootNode != nullptr && !(scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    Collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), mesh);
  }
  const Eigen::Matrix3d to_urdf = ToUrdfFrame(format);
  for (Eigen::Vector3d& v : mesh.vertices) {
    v = (to_urdf * v).cwiseProduct(scale);
    if (!v.allFinite()) throw std::invalid_argument(path + ": a vertex coordinate is not finite");
  }
  Weld(mesh);
  if (mesh.triangles.empty()) throw std::invalid_argument(path + ": the mesh has no triangles (no geometry)");
  // A mirroring scale (an odd number of negative factors) turns the triangles inside out.
  if (scale.prod() < 0.0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  const double extent = (mesh.Max() - mesh.Min()).maxCoeff();
  if (extent > kMaxMeshExtent || extent < kMinMeshExtent) {
    std::ostringstream message;
    message << path << ": <mesh scale=\"" << Format(scale) << "\">: the scaled mesh is " << extent
            << " m across, outside what a robot part can be (" << kMinMeshExtent << " to " << kMaxMeshExtent
            << " m); check the scale and the file's units";
    throw std::invalid_argument(message.str());
  }
  return mesh;
}

using CacheKey = std::tuple<std::string, double, double, double, std::uintmax_t, fs::file_time_type::rep>;

std::mutex& CacheMutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<CacheKey, std::shared_ptr<const TriangleMesh>>& Cache() {
  static std::map<CacheKey, std::shared_ptr<const TriangleMesh>> cache;
  return cache;
}

}  // namespace

Eigen::Vector3d TriangleMesh::Min() const {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3d& v : vertices) lo = lo.cwiseMin(v);
  return lo;
}

Eigen::Vector3d TriangleMesh::Max() const {
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3d& v : vertices) hi = hi.cwiseMax(v);
  return hi;
}

TriangleMesh ReadMeshFile(const std::string& path, const Eigen::Vector3d& scale) {
  CheckScale(path, scale);
  return ReadMesh(path, scale);
}

std::shared_ptr<const TriangleMesh> LoadMesh(const std::string& path, const Eigen::Vector3d& scale) {
  CheckScale(path, scale);
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  const std::uintmax_t size = fs::file_size(path, ec);
  const auto modified = fs::last_write_time(path, ec);
  const CacheKey key{ec ? path : canonical.string(), scale.x(), scale.y(), scale.z(), ec ? 0 : size,
                     ec ? 0 : modified.time_since_epoch().count()};
  // One lock over the read too: two threads asking for the same new mesh read it once.
  std::lock_guard<std::mutex> lock(CacheMutex());
  auto& cache = Cache();
  const auto hit = cache.find(key);
  if (hit != cache.end()) return hit->second;
  auto mesh = std::make_shared<const TriangleMesh>(ReadMesh(path, scale));
  cache.emplace(key, mesh);
  return mesh;
}

std::size_t MeshFilesRead() { return files_read.load(); }

}  // namespace stairplan
