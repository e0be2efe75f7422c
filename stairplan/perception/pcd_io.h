// PCD point clouds, the format of PCL and of ROS's recorders (header VERSION 0.6 or 0.7): DATA
// ascii, binary and binary_compressed (LZF, fields stored one after another). x, y and z must be
// TYPE F fields (float or double, COUNT 1); every other field (rgb, intensity, normals, padding) is
// skipped. Points with a NaN coordinate are skipped: an organised cloud marks a pixel without a
// return that way. VIEWPOINT is not applied (PCL does not apply it either).
#pragma once

#include <string>

#include "stairplan/perception/point_cloud.h"

namespace stairplan {

/// The DATA encodings of a PCD file.
enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

/// True when `bytes` start like a PCD file: comment lines, then a VERSION or FIELDS line.
bool LooksLikePcd(const std::string& bytes);

/// Parses PCD bytes. Errors are FieldError naming `source` and the header field (and its line),
/// or the point and the DATA encoding: a field list whose SIZE, TYPE or COUNT has another number
/// of entries than FIELDS, missing x/y/z, POINTS that disagree with WIDTH x HEIGHT, binary data
/// shorter than POINTS declares, a compressed block that is corrupt or decompresses to another
/// size, infinite coordinates, and a cloud with no finite points.
PointCloud ParsePcd(const std::string& bytes, const std::string& source);

/// Reads a PCD file; a missing file is a FieldError naming the path.
PointCloud ReadPcd(const std::string& path);

}  // namespace stairplan
