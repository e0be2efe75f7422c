// Mesh URIs resolved as ROS does, and meshes read in metres in the URDF's z-up frame: COLLADA's
// units and up axis honoured, STL and OBJ as written, the URDF scale applied; bad files refused
// naming the file; each file read once per process.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "stairplan/kinematics/mesh_loader.h"
#include "stairplan/kinematics/package_path.h"
#include "mesh_files.h"
#include "test_paths.h"

using stairplan::LoadMesh;
using stairplan::PackagePath;
using stairplan::ResolveMeshUri;
using stairplan::TriangleMesh;
using namespace stairplan::testing;
namespace fs = std::filesystem;

namespace {

std::string UriError(const std::string& uri, const std::string& folder, const PackagePath& search) {
  try {
    ResolveMeshUri(uri, folder, search, "r.urdf: <link name=\"shank\">");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string MeshError(const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones()) {
  try {
    LoadMesh(path, scale);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A tetrahedron with its apex 3 units up the file's z axis and a 2-unit leg along its y axis.
std::vector<std::array<Eigen::Vector3d, 3>> TetraTriangles() {
  const Eigen::Vector3d o(0, 0, 0), x(1, 0, 0), y(0, 2, 0), z(0, 0, 3);
  return {{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
}

}  // namespace

TEST_CASE("package:// URIs resolve through the search path as ROS resolves them", "[mesh_loader]") {
  const std::string root = MakeTempDir("package-path");
  fs::create_directories(root + "/a/my_robot/meshes");
  fs::create_directories(root + "/b/src/renamed_folder/meshes");
  WriteBytes(root + "/a/my_robot/meshes/leg.stl", "x");
  WriteBytes(root + "/b/src/renamed_folder/package.xml", "<package>\n  <name>other_robot</name>\n</package>\n");
  WriteBytes(root + "/b/src/renamed_folder/meshes/foot.stl", "x");
  const PackagePath search = PackagePath::FromString(root + "/a:" + root + "/b");
  CHECK(ResolveMeshUri("package://my_robot/meshes/leg.stl", "", search, "r").path == root + "/a/my_robot/meshes/leg.stl");
  // Found by the <name> of its package.xml, two folders down, whatever the folder is called.
  CHECK(ResolveMeshUri("package://other_robot/meshes/foot.stl", "", search, "r").path ==
        root + "/b/src/renamed_folder/meshes/foot.stl");
  // file:// and plain paths; relative ones start at the URDF's folder.
  CHECK(ResolveMeshUri("file://" + root + "/a/my_robot/meshes/leg.stl", "", search, "r").path ==
        root + "/a/my_robot/meshes/leg.stl");
  CHECK(ResolveMeshUri("meshes/leg.stl", root + "/a/my_robot", search, "r").path == root + "/a/my_robot/meshes/leg.stl");

  // An unknown package: the URI, the link and every folder searched.
  const std::string unknown = UriError("package://nobody/meshes/leg.stl", "", search);
  CHECK_THAT(unknown, Catch::Contains("package://nobody/meshes/leg.stl"));
  CHECK_THAT(unknown, Catch::Contains("<link name=\"shank\">"));
  CHECK_THAT(unknown, Catch::Contains(root + "/a, " + root + "/b"));
  CHECK_THAT(UriError("package://nobody/x.stl", "", {}), Catch::Contains("--package-path"));
  // A known package without the file: the path it looked for.
  CHECK_THAT(UriError("package://my_robot/meshes/gone.stl", "", search),
             Catch::Contains(root + "/a/my_robot/meshes/gone.stl"));
  CHECK_THAT(UriError("http://example.com/leg.stl", "", search), Catch::Contains("unsupported URI scheme"));
}

TEST_CASE("ROS_PACKAGE_PATH is split like a PATH", "[mesh_loader]") {
  const char* saved = std::getenv("ROS_PACKAGE_PATH");
  const std::string restore = saved ? saved : "";
  setenv("ROS_PACKAGE_PATH", "/x/one::/y/two:", 1);
  const PackagePath env = PackagePath::FromEnvironment();
  if (saved) {
    setenv("ROS_PACKAGE_PATH", restore.c_str(), 1);
  } else {
    unsetenv("ROS_PACKAGE_PATH");
  }
  REQUIRE(env.folders.size() == 2);
  CHECK(env.folders[0] == "/x/one");
  CHECK(env.folders[1] == "/y/two");
  CHECK(PackagePath::FromString("/y/two:/z").Then(env).folders == std::vector<std::string>{"/y/two", "/z", "/x/one"});
}

TEST_CASE("COLLADA units and up axis are honoured, STL and OBJ are metres as written", "[mesh_loader]") {
  const std::string dir = MakeTempDir("mesh-units");
  const auto tetra = TetraTriangles();
  WriteBytes(dir + "/z_mm.dae", Dae(tetra, "Z_UP", 0.001));
  WriteBytes(dir + "/y_up.dae", Dae(tetra, "Y_UP", 1.0));
  WriteBytes(dir + "/x_up.dae", Dae(tetra, "X_UP", 1.0));
  WriteBytes(dir + "/t.stl", BinaryStl(tetra));
  WriteBytes(dir + "/t.obj", Obj(tetra));
  const auto extent = [](const TriangleMesh& m) { return Eigen::Vector3d(m.Max() - m.Min()); };

  // Z_UP in millimetres: as written, a thousandth of the size.
  const auto mm = LoadMesh(dir + "/z_mm.dae", Eigen::Vector3d::Ones());
  CHECK(extent(*mm).isApprox(Eigen::Vector3d(0.001, 0.002, 0.003), 1e-6));  // the file's floats
  CHECK(mm->vertices.size() == 4);
  CHECK(mm->triangles.size() == 4);
  // Y_UP: the file's +y (2 long) is up; its +z (3 long) points to -y in the URDF frame.
  const auto y_up = LoadMesh(dir + "/y_up.dae", Eigen::Vector3d::Ones());
  CHECK(y_up->Max().isApprox(Eigen::Vector3d(1, 0, 2), 1e-9));
  CHECK(y_up->Min().isApprox(Eigen::Vector3d(0, -3, 0), 1e-9));
  // X_UP: the file's +x (1 long) is up.
  CHECK(LoadMesh(dir + "/x_up.dae", Eigen::Vector3d::Ones())->Max().z() == Approx(1.0));
  for (const std::string name : {"t.stl", "t.obj"}) {
    INFO(name);
    const auto mesh = LoadMesh(dir + "/" + name, Eigen::Vector3d::Ones());
    CHECK(mesh->Max().isApprox(Eigen::Vector3d(1, 2, 3), 1e-6));
    CHECK(mesh->vertices.size() == 4);  // the STL's twelve corners welded to four
  }
  // The URDF scale, including a mirroring one (which keeps the triangles facing out).
  const auto scaled = LoadMesh(dir + "/t.stl", Eigen::Vector3d(0.5, -1.0, 2.0));
  CHECK(scaled->Min().isApprox(Eigen::Vector3d(0, -2, 0), 1e-6));
  CHECK(scaled->Max().isApprox(Eigen::Vector3d(0.5, 0, 6), 1e-6));
  const Eigen::Vector3d centroid = 0.25 * (scaled->vertices[0] + scaled->vertices[1] + scaled->vertices[2] + scaled->vertices[3]);
  for (const auto& t : scaled->triangles) {
    const Eigen::Vector3d& a = scaled->vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d n = (scaled->vertices[static_cast<std::size_t>(t[1])] - a).cross(scaled->vertices[static_cast<std::size_t>(t[2])] - a);
    CHECK(n.dot(a - centroid) > 0.0);
  }
}

TEST_CASE("a mesh file is read once per process", "[mesh_loader]") {
  const std::string dir = MakeTempDir("mesh-cache");
  WriteBytes(dir + "/t.stl", BinaryStl(TetraTriangles()));
  const std::size_t before = stairplan::MeshFilesRead();
  const auto first = LoadMesh(dir + "/t.stl", Eigen::Vector3d::Ones());
  const auto again = LoadMesh(dir + "/./t.stl", Eigen::Vector3d::Ones());
  CHECK(first == again);
  CHECK(stairplan::MeshFilesRead() == before + 1);
  // Another scale is another mesh.
  CHECK(LoadMesh(dir + "/t.stl", Eigen::Vector3d::Constant(0.5)) != first);
  CHECK(stairplan::MeshFilesRead() == before + 2);
  // ReadMeshFile reads the file every time, leaving the cache alone, and gives the same mesh.
  const TriangleMesh uncached = stairplan::ReadMeshFile(dir + "/t.stl", Eigen::Vector3d::Ones());
  CHECK(stairplan::MeshFilesRead() == before + 3);
  CHECK(uncached.vertices == first->vertices);
  CHECK(uncached.triangles == first->triangles);
  CHECK(LoadMesh(dir + "/t.stl", Eigen::Vector3d::Ones()) == first);
  CHECK(stairplan::MeshFilesRead() == before + 3);
}

TEST_CASE("bad mesh files are refused naming the file", "[mesh_loader]") {
  const std::string dir = MakeTempDir("mesh-bad");
  const auto tetra = TetraTriangles();
  std::string truncated = BinaryStl(tetra);
  truncated.resize(truncated.size() - 30);
  WriteBytes(dir + "/cut.stl", truncated);
  WriteBytes(dir + "/header.stl", BinaryStl(tetra, 40));  // claims 40 triangles, holds 4
  WriteBytes(dir + "/empty.obj", "");
  WriteBytes(dir + "/comments.obj", "# exported with nothing in it\no empty\n");
  WriteBytes(dir + "/face_only.obj", "f 1 2 3\n");  // one line: assimp's atoi would find no NUL after it
  WriteBytes(dir + "/no_geometry.dae", Dae({}, "Z_UP", 1.0));
  WriteBytes(dir + "/flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  WriteBytes(dir + "/t.stl", BinaryStl(tetra));
  WriteBytes(dir + "/t.ply", "ply\n");

  CHECK_THAT(MeshError(dir + "/absent.stl"), Catch::Contains(dir + "/absent.stl"));
  CHECK_THAT(MeshError(dir + "/cut.stl"), Catch::Contains(dir + "/cut.stl: truncated"));
  CHECK_THAT(MeshError(dir + "/header.stl"), Catch::Contains(dir + "/header.stl: truncated"));
  CHECK_THAT(MeshError(dir + "/empty.obj"), Catch::StartsWith(dir + "/empty.obj"));
  CHECK_THAT(MeshError(dir + "/comments.obj"), Catch::StartsWith(dir + "/comments.obj"));
  CHECK_THAT(MeshError(dir + "/face_only.obj"), Catch::Contains(dir + "/face_only.obj: the mesh has no triangles"));
  CHECK_THAT(MeshError(dir + "/no_geometry.dae"), Catch::Contains(dir + "/no_geometry.dae: the mesh has no triangles"));
  CHECK_THAT(MeshError(dir + "/t.ply"), Catch::Contains("unsupported mesh format"));
  CHECK_THAT(MeshError(dir + "/t.stl", Eigen::Vector3d(1000, 1000, 1000)), Catch::Contains("3000 m across"));
  CHECK_THAT(MeshError(dir + "/t.stl", Eigen::Vector3d(1e-6, 1e-6, 1e-6)), Catch::Contains("<mesh scale="));
  CHECK_THAT(MeshError(dir + "/t.stl", Eigen::Vector3d(1, 0, 1)), Catch::Contains("non-zero"));
  CHECK_THAT(MeshError(dir + "/t.stl", Eigen::Vector3d(1, NAN, 1)), Catch::Contains(dir + "/t.stl"));
  // A flat mesh loads (its hull is refused by the collision model, naming it).
  CHECK(MeshError(dir + "/flat.obj").empty());
}
