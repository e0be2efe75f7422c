// Whitespace-separated XYZ text: one point per line ("x y z", extra columns ignored), blank lines
// and lines starting with '#' skipped.
#pragma once

#include <string>

#include "stairplan/perception/point_cloud.h"

namespace stairplan {

/// Parses XYZ text; `source` names it in errors ("<source>: line N: ..."). No points is an error.
PointCloud ParseXyz(const std::string& text, const std::string& source);
/// Reads an XYZ file; a missing file is a FieldError naming the path.
PointCloud ReadXyz(const std::string& path);
/// Writes the cloud as XYZ text with millimetre-and-better precision.
std::string XyzText(const PointCloud& cloud);

}  // namespace stairplan
