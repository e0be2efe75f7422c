// libFuzzer target: the collision-mesh reader (assimp's STL, OBJ and COLLADA importers behind our
// size, triangle and extent checks). The first byte picks the format, the rest is the file, written
// to a scratch folder because assimp reads from disk. The reader's cache is bypassed
// (ReadMeshFile), so that the inputs it accepts are not all kept in memory.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_check.h"
#include "stairplan/kinematics/mesh_loader.h"

namespace {

// One folder per process, so that fuzzing jobs side by side do not overwrite each other's file;
// removed when the fuzzer exits.
class ScratchFolder {
 public:
  ScratchFolder()
      : path_(std::filesystem::temp_directory_path() / ("stairplan-fuzz-mesh-" + std::to_string(getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void CheckMesh(const stairplan::TriangleMesh& mesh) {
  bool ok = !mesh.triangles.empty();
  for (const auto& v : mesh.vertices) ok = ok && v.allFinite();
  for (const auto& t : mesh.triangles) {
    for (const int k : t) ok = ok && k >= 0 && static_cast<std::size_t>(k) < mesh.vertices.size();
  }
  const double extent = ok ? (mesh.Max() - mesh.Min()).maxCoeff() : 0.0;
  if (!ok || !(extent >= stairplan::kMinMeshExtent && extent <= stairplan::kMaxMeshExtent)) {
    std::fprintf(stderr, "finding: the mesh reader returned an empty, non-finite, badly indexed or out-of-range mesh\n");
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".stl", ".obj", ".dae"};
  const std::string name = std::string("fuzz") + kExtensions[data[0] % 3];
  static const ScratchFolder folder;
  const std::string path = (folder.path() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data + 1),
                                                                 static_cast<std::streamsize>(size - 1));
  try {
    CheckMesh(stairplan::ReadMeshFile(path, Eigen::Vector3d::Ones()));
  } catch (const std::invalid_argument& e) {
    stairplan::fuzz::CheckNamesSource(e, name.c_str());
  }
  return 0;
}
