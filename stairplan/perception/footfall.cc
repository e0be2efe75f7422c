#include "stairplan/perception/footfall.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

std::string Trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(Trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

double Number(const std::string& text, const std::string& where, const char* column) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0') {
    throw FieldError(where, std::string("column '") + column + "' is not a number ('" + text + "')");
  }
  if (!std::isfinite(v)) throw FieldError(where, std::string("column '") + column + "' is not finite ('" + text + "')");
  return v;
}

}  // namespace

std::vector<Footfall> ParseFootfallCsv(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  bool header = false;
  std::vector<Footfall> footfalls;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::string where = source + ": line " + std::to_string(line_number);
    const std::vector<std::string> fields = SplitCsv(trimmed);
    if (!header) {
      if (fields != std::vector<std::string>{"t", "leg", "x", "y", "z"}) {
        throw FieldError(where, "the header must be 't,leg,x,y,z' (got '" + trimmed + "')");
      }
      header = true;
      continue;
    }
    if (fields.size() != 5) throw FieldError(where, "expected 5 columns t,leg,x,y,z (got " + std::to_string(fields.size()) + ")");
    Footfall f;
    f.t = Number(fields[0], where, "t");
    f.leg = fields[1];
    if (f.leg.empty()) throw FieldError(where, "column 'leg' is empty");
    f.position = Eigen::Vector3d(Number(fields[2], where, "x"), Number(fields[3], where, "y"), Number(fields[4], where, "z"));
    footfalls.push_back(f);
  }
  if (!header) throw FieldError(source + ": line " + std::to_string(line_number + 1), "empty file (expected the header 't,leg,x,y,z')");
  return footfalls;
}

std::vector<Footfall> ReadFootfallCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FieldError(path, "cannot open the footfall file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseFootfallCsv(buffer.str(), path);
}

std::string FootfallCsv(const std::vector<Footfall>& footfalls) {
  std::ostringstream out;
  out.precision(9);
  out << "t,leg,x,y,z\n";
  for (const Footfall& f : footfalls) {
    out << f.t << ',' << f.leg << ',' << f.position.x() << ',' << f.position.y() << ',' << f.position.z() << '\n';
  }
  return out.str();
}

}  // namespace stairplan
