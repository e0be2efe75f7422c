// PLY point clouds: ascii and binary little-endian, x y z stored as float or double. Other
// vertex properties (colours, normals) and elements without lists before the vertices are skipped.
#pragma once

#include <string>

#include "stairplan/perception/point_cloud.h"

namespace stairplan {

/// The PLY encodings PlyBytes() writes (ParsePly() also reads them).
enum class PlyFormat { kAscii, kBinaryLittleEndian };

/// Parses PLY bytes; errors name `source` and the line (ascii, header) or the vertex (binary).
/// Truncated data, NaN or infinite coordinates and a cloud with no vertices are errors.
PointCloud ParsePly(const std::string& bytes, const std::string& source);
/// Reads a PLY file; a missing file is a FieldError naming the path.
PointCloud ReadPly(const std::string& path);
/// Serialises the cloud as PLY with double (or float) coordinates.
std::string PlyBytes(const PointCloud& cloud, PlyFormat format, bool as_float = false);

}  // namespace stairplan
