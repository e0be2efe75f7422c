#include "stairplan/perception/xyz_io.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "stairplan/geometry/field_error.h"

namespace stairplan {

PointCloud ParseXyz(const std::string& text, const std::string& source) {
  PointCloud cloud;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::string token;
    double xyz[3];
    int count = 0;
    while (count < 3 && fields >> token) {
      char* end = nullptr;
      xyz[count] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        throw FieldError(source + ": line " + std::to_string(line_number), "'" + token + "' is not a number");
      }
      if (!std::isfinite(xyz[count])) {
        throw FieldError(source + ": line " + std::to_string(line_number), "non-finite coordinate '" + token + "'");
      }
      ++count;
    }
    if (count < 3) {
      throw FieldError(source + ": line " + std::to_string(line_number), "needs three numbers x y z");
    }
    cloud.points.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  if (cloud.empty()) throw FieldError(source + ": line " + std::to_string(line_number + 1), "no points in the file");
  return cloud;
}

PointCloud ReadXyz(const std::string& path) { return ParseXyz(ReadCloudFile(path), path); }

std::string XyzText(const PointCloud& cloud) {
  std::ostringstream out;
  out.precision(9);
  for (const auto& p : cloud.points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  return out.str();
}

}  // namespace stairplan
