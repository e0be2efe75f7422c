#include "stairplan/perception/ply_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <vector>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

struct Property {
  std::string name;
  int bytes = 0;          // size of the scalar in binary files
  bool is_list = false;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
  int line = 0;  // the header line that declared it
};

int ScalarBytes(const std::string& type) {
  static const std::map<std::string, int> kSizes = {
      {"char", 1}, {"uchar", 1}, {"int8", 1}, {"uint8", 1}, {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4}, {"uint", 4}, {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? 0 : it->second;
}

std::string Line(const std::string& source, int line) { return source + ": line " + std::to_string(line); }

double Checked(double v, const std::string& where, const char* axis) {
  if (!std::isfinite(v)) throw FieldError(where, std::string("non-finite ") + axis + " coordinate");
  return v;
}

}  // namespace

PointCloud ParsePly(const std::string& bytes, const std::string& source) {
  if (bytes.empty()) throw FieldError(Line(source, 1), "empty file (expected a PLY header)");
  std::size_t pos = 0;
  int line_number = 0;
  const auto next_line = [&](std::string& line) {
    if (pos >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    ++line_number;
    return true;
  };
  std::string line;
  if (!next_line(line) || line != "ply") throw FieldError(Line(source, 1), "not a PLY file (first line must be 'ply')");
  std::string format;
  std::vector<Element> elements;
  bool ended = false;
  while (next_line(line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      words >> format;
      if (format != "ascii" && format != "binary_little_endian") {
        throw FieldError(Line(source, line_number), "unsupported PLY format '" + format + "' (ascii or binary_little_endian)");
      }
    } else if (keyword == "element") {
      Element e;
      e.line = line_number;
      if (!(words >> e.name >> e.count) || e.count < 0) throw FieldError(Line(source, line_number), "bad element line");
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) throw FieldError(Line(source, line_number), "property before any element");
      std::string type;
      words >> type;
      Property p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.is_list = true;
      } else {
        p.bytes = ScalarBytes(type);
        words >> p.name;
        if (p.bytes == 0) throw FieldError(Line(source, line_number), "unknown property type '" + type + "'");
        if ((p.name == "x" || p.name == "y" || p.name == "z") && elements.back().name == "vertex" && p.bytes < 4) {
          throw FieldError(Line(source, line_number), "coordinate '" + p.name + "' must be float or double");
        }
        if ((p.name == "x" || p.name == "y" || p.name == "z") && type.find("int") != std::string::npos) {
          throw FieldError(Line(source, line_number), "coordinate '" + p.name + "' must be float or double");
        }
      }
      elements.back().properties.push_back(p);
    } else if (keyword == "end_header") {
      ended = true;
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      throw FieldError(Line(source, line_number), "unknown header keyword '" + keyword + "'");
    }
  }
  if (!ended) throw FieldError(Line(source, line_number + 1), "truncated PLY header (no end_header)");
  if (format.empty()) throw FieldError(Line(source, line_number), "PLY header has no format line");

  PointCloud cloud;
  const bool binary = format == "binary_little_endian";
  for (const Element& e : elements) {
    const bool vertex = e.name == "vertex";
    int ix = -1, iy = -1, iz = -1;
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const std::string& n = e.properties[i].name;
      if (n == "x") ix = static_cast<int>(i);
      if (n == "y") iy = static_cast<int>(i);
      if (n == "z") iz = static_cast<int>(i);
    }
    if (vertex && (ix < 0 || iy < 0 || iz < 0)) throw FieldError(Line(source, e.line), "vertex element needs x, y and z");
    if (binary) {
      int stride = 0;
      for (const Property& p : e.properties) {
        if (p.is_list) {
          if (vertex) throw FieldError(Line(source, e.line), "list properties on vertices are not supported");
          break;  // elements after a list element cannot be located; the vertices must come first
        }
        stride += p.bytes;
      }
      const bool has_list = std::any_of(e.properties.begin(), e.properties.end(), [](const Property& p) { return p.is_list; });
      if (has_list) break;
      if (!vertex) {
        // Skipped whole: an element of no bytes once looped e.count (up to 2^63) times (fuzzer).
        const std::size_t left = bytes.size() - std::min(pos, bytes.size());
        if (stride > 0 && static_cast<unsigned long long>(e.count) > left / static_cast<std::size_t>(stride)) {
          throw FieldError(source + ": " + e.name + " (byte " + std::to_string(pos) + ")",
                           "truncated binary data: the header declares " + std::to_string(e.count) + " " + e.name + " entries");
        }
        pos += static_cast<std::size_t>(stride) * static_cast<std::size_t>(e.count);
        continue;
      }
      for (long long v = 0; v < e.count; ++v) {
        if (pos + static_cast<std::size_t>(stride) > bytes.size()) {
          throw FieldError(source + ": " + e.name + " " + std::to_string(v) + " (byte " + std::to_string(pos) + ")",
                           "truncated binary data: the header declares " + std::to_string(e.count) + " " + e.name + " entries");
        }
        if (vertex) {
          double xyz[3] = {0, 0, 0};
          std::size_t offset = pos;
          for (std::size_t i = 0; i < e.properties.size(); ++i) {
            const int which = static_cast<int>(i) == ix ? 0 : static_cast<int>(i) == iy ? 1 : static_cast<int>(i) == iz ? 2 : -1;
            if (which >= 0) {
              if (e.properties[i].bytes == 4) {
                float f;
                std::memcpy(&f, bytes.data() + offset, 4);
                xyz[which] = f;
              } else {
                std::memcpy(&xyz[which], bytes.data() + offset, 8);
              }
            }
            offset += static_cast<std::size_t>(e.properties[i].bytes);
          }
          const std::string where = source + ": vertex " + std::to_string(v);
          cloud.points.emplace_back(Checked(xyz[0], where, "x"), Checked(xyz[1], where, "y"), Checked(xyz[2], where, "z"));
        }
        pos += static_cast<std::size_t>(stride);
      }
    } else {
      for (long long v = 0; v < e.count; ++v) {
        if (!next_line(line)) {
          throw FieldError(Line(source, line_number + 1), "file ends after " + std::to_string(v) + " of " +
                                                              std::to_string(e.count) + " " + e.name + " lines");
        }
        if (!vertex) continue;
        std::istringstream fields(line);
        std::vector<double> values;
        std::string token;
        while (fields >> token) {
          char* end = nullptr;
          const double value = std::strtod(token.c_str(), &end);
          if (end == token.c_str() || *end != '\0') throw FieldError(Line(source, line_number), "'" + token + "' is not a number");
          values.push_back(value);
        }
        if (values.size() < e.properties.size()) {
          throw FieldError(Line(source, line_number), "expected " + std::to_string(e.properties.size()) + " values, got " +
                                                          std::to_string(values.size()));
        }
        const std::string where = Line(source, line_number);
        cloud.points.emplace_back(Checked(values[static_cast<std::size_t>(ix)], where, "x"),
                                  Checked(values[static_cast<std::size_t>(iy)], where, "y"),
                                  Checked(values[static_cast<std::size_t>(iz)], where, "z"));
      }
    }
    if (vertex) break;  // nothing after the vertices is needed
  }
  if (cloud.empty()) throw FieldError(Line(source, line_number), "the PLY file has no vertices");
  return cloud;
}

PointCloud ReadPly(const std::string& path) { return ParsePly(ReadCloudFile(path), path); }

std::string PlyBytes(const PointCloud& cloud, PlyFormat format, bool as_float) {
  std::ostringstream out;
  const char* type = as_float ? "float" : "double";
  out << "ply\nformat " << (format == PlyFormat::kAscii ? "ascii" : "binary_little_endian") << " 1.0\n"
      << "comment stairplan point cloud\nelement vertex " << cloud.size() << "\nproperty " << type << " x\nproperty "
      << type << " y\nproperty " << type << " z\nend_header\n";
  if (format == PlyFormat::kAscii) {
    out.precision(as_float ? 7 : 12);
    for (const auto& p : cloud.points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  } else {
    for (const auto& p : cloud.points) {
      for (int i = 0; i < 3; ++i) {
        if (as_float) {
          const float f = static_cast<float>(p[i]);
          out.write(reinterpret_cast<const char*>(&f), 4);
        } else {
          const double d = p[i];
          out.write(reinterpret_cast<const char*>(&d), 8);
        }
      }
    }
  }
  return out.str();
}

}  // namespace stairplan
