// Footfalls: where and when a foot touched the ground, as logged by a robot (PCT/US2021/022953
// ("Identifying stairs from footfalls") [0045]). CSV columns t, leg, x, y, z with a header line;
// the readers name the file and line of errors.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace stairplan {

/// One footfall: when and where a foot touched down.
struct Footfall {
  double t = 0.0;          ///< touchdown time [s]
  std::string leg;         ///< e.g. "LF"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< contact point in the world [m]
};

/// Parses footfall CSV (header "t,leg,x,y,z"; blank lines and '#' comments skipped). Throws
/// FieldError "<source>: line N" for a bad header, a wrong column count, a non-number or NaN.
std::vector<Footfall> ParseFootfallCsv(const std::string& text, const std::string& source);
/// Reads a footfall CSV file; a missing file is a FieldError naming the path.
std::vector<Footfall> ReadFootfallCsv(const std::string& path);
/// Writes footfalls as CSV with the header.
std::string FootfallCsv(const std::vector<Footfall>& footfalls);

}  // namespace stairplan
