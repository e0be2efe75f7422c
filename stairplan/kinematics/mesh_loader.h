// Reading the collision meshes a URDF names (STL, OBJ, COLLADA) with assimp into triangle meshes in
// metres, in the frame the URDF's <collision> places them (z up), with the URDF's scale applied.
// Each file is read once per process: a robot loaded again, a sweep point or another thread gets
// the mesh already in memory (keyed by path, scale, size and modification time).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// A triangle mesh: vertices in metres, triangles as counter-clockwise (outward) index triples.
struct TriangleMesh {
  std::string file;                          ///< the file it was read from
  std::vector<Eigen::Vector3d> vertices;     ///< [m]
  /// Index triples into `vertices`, counter-clockwise seen from outside.
  std::vector<std::array<int, 3>> triangles;

  /// Componentwise lower bounds of the vertices [m].
  Eigen::Vector3d Min() const;
  /// Componentwise upper bounds of the vertices [m].
  Eigen::Vector3d Max() const;
};

/// The largest extent a collision mesh may have after scaling: no leg link is 10 m long, so a
/// mesh that large was scaled wrong (a metre file given a millimetre scale the other way round).
constexpr double kMaxMeshExtent = 10.0;  // [m]
/// ... and the smallest: a tenth of a millimetre across is a scale applied twice.
constexpr double kMinMeshExtent = 1e-4;  // [m]

/// Reads `path` (.stl, .obj or .dae, case-insensitive) and scales it by `scale` (the URDF
/// `<mesh scale>`). Units and up axis: STL and OBJ carry neither and are taken as metres in the
/// URDF's frame (as ROS does); COLLADA's `<unit meter>` and `<up_axis>` are honoured, so its up axis
/// becomes +z. Throws std::invalid_argument starting with the file's path: missing or unreadable,
/// not a mesh assimp can read (a truncated STL), no triangles (an empty OBJ, a DAE without
/// geometry), non-finite coordinates, or a scale that is zero, not finite, or makes the mesh
/// larger than kMaxMeshExtent or smaller than kMinMeshExtent.
std::shared_ptr<const TriangleMesh> LoadMesh(const std::string& path, const Eigen::Vector3d& scale);

/// Reads `path` as LoadMesh does (same checks, same errors) but from disk on every call, leaving
/// the cache alone: for a caller that reads many different files, each once (the mesh fuzzer,
/// whose cache would otherwise keep every input it accepted).
TriangleMesh ReadMeshFile(const std::string& path, const Eigen::Vector3d& scale);

/// How many mesh files this process has read from disk (cache hits do not count).
std::size_t MeshFilesRead();

}  // namespace stairplan
