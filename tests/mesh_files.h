// Small mesh files written by tests into their temporary folders (no mesh fixtures in the repo):
// a box as binary STL, OBJ and COLLADA text, and the bad files of the bad-input table.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace stairplan::testing {

/// The 12 outward triangles of the box [lo, hi].
inline std::vector<std::array<Eigen::Vector3d, 3>> BoxTriangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> c;
  for (int i = 0; i < 8; ++i) c.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  for (const auto& f : faces) triangles.push_back({c[f[0]], c[f[1]], c[f[2]]});
  return triangles;
}

/// A binary STL of `triangles` (header "solid ..." as some exporters write it); `count` overrides
/// the triangle count in the header (for truncated files).
inline std::string BinaryStl(const std::vector<std::array<Eigen::Vector3d, 3>>& triangles, long count = -1) {
  std::string out(80, ' ');
  out.replace(0, 10, "solid test");
  const std::uint32_t n = static_cast<std::uint32_t>(count < 0 ? static_cast<long>(triangles.size()) : count);
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : triangles) {
    const Eigen::Vector3d normal = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    float values[12];
    for (int k = 0; k < 3; ++k) values[k] = static_cast<float>(normal[k]);
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 3; ++k) values[3 + 3 * v + k] = static_cast<float>(t[static_cast<std::size_t>(v)][k]);
    }
    out.append(reinterpret_cast<const char*>(values), sizeof(values));
    out.append(2, '\0');
  }
  return out;
}

/// An OBJ of `triangles` (one vertex line per corner).
inline std::string Obj(const std::vector<std::array<Eigen::Vector3d, 3>>& triangles) {
  std::ostringstream out;
  for (const auto& t : triangles) {
    for (const auto& v : t) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) out << "f " << 3 * i + 1 << " " << 3 * i + 2 << " " << 3 * i + 3 << "\n";
  return out.str();
}

/// A COLLADA file of `triangles` with the given <up_axis> and <unit meter>; none when empty.
inline std::string Dae(const std::vector<std::array<Eigen::Vector3d, 3>>& triangles, const std::string& up_axis,
                       double meter) {
  std::ostringstream points, indices;
  for (const auto& t : triangles) {
    for (const auto& v : t) points << v.x() << " " << v.y() << " " << v.z() << " ";
  }
  for (std::size_t i = 0; i < 3 * triangles.size(); ++i) indices << i << " ";
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
      << "<asset><unit name=\"u\" meter=\"" << meter << "\"/><up_axis>" << up_axis << "</up_axis></asset>\n";
  if (!triangles.empty()) {
    const std::size_t n = 3 * triangles.size();
    out << "<library_geometries><geometry id=\"g\"><mesh>\n"
        << "<source id=\"p\"><float_array id=\"pa\" count=\"" << 3 * n << "\">" << points.str() << "</float_array>"
        << "<technique_common><accessor source=\"#pa\" count=\"" << n << "\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
        << "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
        << "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
        << "<triangles count=\"" << triangles.size() << "\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>"
        << indices.str() << "</p></triangles>\n</mesh></geometry></library_geometries>\n";
  }
  out << "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\" name=\"n\">"
      << (triangles.empty() ? "" : "<instance_geometry url=\"#g\"/>") << "</node></visual_scene></library_visual_scenes>\n"
      << "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
  return out.str();
}

inline void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace stairplan::testing
