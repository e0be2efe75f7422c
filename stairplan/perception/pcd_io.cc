#include "stairplan/perception/pcd_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/lzf.h"

namespace stairplan {
namespace {

// Bounds that keep a hostile header from asking for gigabytes per point (PCL's widest descriptor,
// VFH, has 308 values).
constexpr long long kMaxCount = 1 << 16;
constexpr std::size_t kMaxFields = 4096;
constexpr long long kMaxValuesPerPoint = 1 << 16;

struct PcdField {
  std::string name;
  int size = 0;
  char type = 0;
  long long count = 1;
  std::size_t bytes() const { return static_cast<std::size_t>(size) * static_cast<std::size_t>(count); }
};

struct PcdHeader {
  std::vector<PcdField> fields;
  int fields_line = 0;
  long long width = -1, height = -1, points = -1;
  int points_line = 0;
  PcdEncoding encoding = PcdEncoding::kAscii;
  std::size_t data_start = 0;  // byte after the DATA line
  int data_line = 0;
  std::size_t point_bytes = 0;
  int xyz[3] = {-1, -1, -1};   // field indices
};

std::string Line(const std::string& source, int line, const std::string& keyword) {
  return source + ": line " + std::to_string(line) + " (" + keyword + ")";
}

long long Integer(const std::string& token, const std::string& where, long long lo, long long hi) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (end == token.c_str() || *end != '\0' || errno == ERANGE || value < lo || value > hi) {
    throw FieldError(where, "'" + token + "' is not a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
  }
  return value;
}

// SIZE, TYPE and COUNT each give one entry per field of FIELDS.
void RequireOnePerField(const PcdHeader& h, std::size_t entries, const std::string& where) {
  if (h.fields.empty()) throw FieldError(where, "comes before FIELDS");
  if (entries != h.fields.size()) {
    throw FieldError(where, "has " + std::to_string(entries) + " entries, FIELDS names " + std::to_string(h.fields.size()));
  }
}

void ParseHeaderLine(const std::string& keyword, const std::vector<std::string>& values, int line,
                     const std::string& source, PcdHeader& h) {
  const std::string where = Line(source, line, keyword);
  if (keyword == "VERSION" || keyword == "VIEWPOINT") return;
  if (keyword == "FIELDS" || keyword == "COLUMNS") {
    if (values.empty() || values.size() > kMaxFields) {
      throw FieldError(where, "needs 1 to " + std::to_string(kMaxFields) + " field names");
    }
    h.fields.assign(values.size(), PcdField{});
    for (std::size_t i = 0; i < values.size(); ++i) h.fields[i].name = values[i];
    h.fields_line = line;
    return;
  }
  if (keyword == "SIZE") {
    RequireOnePerField(h, values.size(), where);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const long long size = Integer(values[i], where, 1, 8);
      if (size != 1 && size != 2 && size != 4 && size != 8) {
        throw FieldError(where, "field '" + h.fields[i].name + "': SIZE must be 1, 2, 4 or 8");
      }
      h.fields[i].size = static_cast<int>(size);
    }
  } else if (keyword == "TYPE") {
    RequireOnePerField(h, values.size(), where);
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (values[i] != "F" && values[i] != "I" && values[i] != "U") {
        throw FieldError(where, "field '" + h.fields[i].name + "': TYPE must be F, I or U (got '" + values[i] + "')");
      }
      h.fields[i].type = values[i][0];
    }
  } else if (keyword == "COUNT") {
    RequireOnePerField(h, values.size(), where);
    for (std::size_t i = 0; i < values.size(); ++i) h.fields[i].count = Integer(values[i], where, 1, kMaxCount);
  } else if (keyword == "WIDTH" || keyword == "HEIGHT" || keyword == "POINTS") {
    if (values.size() != 1) throw FieldError(where, "needs one number");
    const long long value = Integer(values[0], where, 0, std::numeric_limits<long long>::max());
    if (keyword == "WIDTH") h.width = value;
    if (keyword == "HEIGHT") h.height = value;
    if (keyword == "POINTS") {
      h.points = value;
      h.points_line = line;
    }
  } else if (keyword == "DATA") {
    const std::string encoding = values.empty() ? "" : values[0];
    if (encoding == "ascii") h.encoding = PcdEncoding::kAscii;
    else if (encoding == "binary") h.encoding = PcdEncoding::kBinary;
    else if (encoding == "binary_compressed") h.encoding = PcdEncoding::kBinaryCompressed;
    else throw FieldError(where, "unsupported encoding '" + encoding + "' (ascii, binary or binary_compressed)");
  } else {
    throw FieldError(where, "unknown header keyword (not a PCD header?)");
  }
}

// The field list is complete and x, y, z are floating point; POINTS agrees with WIDTH x HEIGHT.
void CheckHeader(PcdHeader& h, const std::string& source) {
  const std::string data = Line(source, h.data_line, "DATA");
  if (h.fields.empty()) throw FieldError(data, "the header has no FIELDS line");
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    const PcdField& f = h.fields[i];
    const std::string where = Line(source, h.fields_line, "FIELDS") + " field '" + f.name + "'";
    if (f.size == 0) throw FieldError(where, "has no SIZE (the header needs a SIZE line)");
    if (f.type == 0) throw FieldError(where, "has no TYPE (the header needs a TYPE line)");
    if (f.type == 'F' && f.size != 4 && f.size != 8) throw FieldError(where, "TYPE F needs SIZE 4 or 8");
    const int axis = f.name == "x" ? 0 : f.name == "y" ? 1 : f.name == "z" ? 2 : -1;
    if (axis >= 0) {
      if (f.type != 'F' || f.count != 1) throw FieldError(where, "must be TYPE F (float or double) with COUNT 1");
      if (h.xyz[axis] < 0) h.xyz[axis] = static_cast<int>(i);
    }
    h.point_bytes += f.bytes();
  }
  if (h.xyz[0] < 0 || h.xyz[1] < 0 || h.xyz[2] < 0) throw FieldError(Line(source, h.fields_line, "FIELDS"), "needs x, y and z");
  long long values = 0;
  for (const PcdField& f : h.fields) values += f.count;
  if (values > kMaxValuesPerPoint) {
    throw FieldError(Line(source, h.fields_line, "FIELDS"), "a point of " + std::to_string(values) +
                                                                 " values (COUNT summed over the fields); at most " +
                                                                 std::to_string(kMaxValuesPerPoint));
  }
  if (h.height < 0) h.height = 1;
  long long grid = -1;  // WIDTH x HEIGHT, when WIDTH is given
  if (h.width >= 0) {
    if (h.height > 0 && h.width > std::numeric_limits<long long>::max() / h.height) {
      throw FieldError(data, "WIDTH x HEIGHT is too large");
    }
    grid = h.width * h.height;
  }
  if (h.points < 0) {
    if (grid < 0) throw FieldError(data, "the header has neither POINTS nor WIDTH");
    h.points = grid;
  } else if (grid >= 0 && grid != h.points) {
    throw FieldError(Line(source, h.points_line, "POINTS"), std::to_string(h.points) + " points, but WIDTH x HEIGHT is " +
                                                               std::to_string(h.width) + " x " + std::to_string(h.height));
  }
  if (h.points == 0) throw FieldError(Line(source, h.points_line ? h.points_line : h.data_line, "POINTS"), "the cloud has no points");
}

PcdHeader ParseHeader(const std::string& bytes, const std::string& source) {
  PcdHeader h;
  std::size_t pos = 0;
  int line_number = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::string line = bytes.substr(pos, end - pos);
    pos = std::min(end + 1, bytes.size());
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword[0] == '#') continue;
    std::vector<std::string> values;
    for (std::string v; words >> v && values.size() <= kMaxFields;) values.push_back(v);
    ParseHeaderLine(keyword, values, line_number, source, h);
    if (keyword == "DATA") {
      h.data_line = line_number;
      h.data_start = pos;
      CheckHeader(h, source);
      return h;
    }
  }
  if (line_number == 0) throw FieldError(source + ": line 1", "empty file (expected a PCD header)");
  throw FieldError(source + ": line " + std::to_string(line_number + 1) + " (DATA)", "truncated PCD header (no DATA line)");
}

double ReadFloat(const std::uint8_t* p, int size) {
  if (size == 4) {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  double d;
  std::memcpy(&d, p, 8);
  return d;
}

// Appends the point unless a coordinate is NaN (no return); an infinite one is an error.
void AddPoint(PointCloud& cloud, const double xyz[3], const std::string& where) {
  if (std::isnan(xyz[0]) || std::isnan(xyz[1]) || std::isnan(xyz[2])) return;
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(xyz[axis])) throw FieldError(where, std::string("infinite ") + "xyz"[axis] + " coordinate");
  }
  cloud.points.emplace_back(xyz[0], xyz[1], xyz[2]);
}

void ReadAscii(const std::string& bytes, const PcdHeader& h, const std::string& source, PointCloud& cloud) {
  std::size_t values_per_point = 0;
  for (const PcdField& f : h.fields) values_per_point += static_cast<std::size_t>(f.count);
  std::vector<int> value_axis(values_per_point, -1);  // which coordinate each value of a row is
  std::size_t column = 0;
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      if (h.xyz[axis] == static_cast<int>(i)) value_axis[column] = axis;
    }
    column += static_cast<std::size_t>(h.fields[i].count);
  }
  std::size_t pos = h.data_start;
  int line_number = h.data_line;
  long long read = 0;
  while (read < h.points) {
    if (pos >= bytes.size()) {
      throw FieldError(Line(source, line_number + 1, "POINTS"), "file ends after " + std::to_string(read) + " of " +
                                                                     std::to_string(h.points) + " points");
    }
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::istringstream fields(bytes.substr(pos, end - pos));
    pos = end + 1;
    ++line_number;
    double xyz[3] = {0, 0, 0};
    std::size_t count = 0;
    for (std::string token; fields >> token; ++count) {
      char* stop = nullptr;
      const double value = std::strtod(token.c_str(), &stop);
      if (stop == token.c_str() || *stop != '\0') {
        throw FieldError(source + ": line " + std::to_string(line_number), "'" + token + "' is not a number");
      }
      if (count < values_per_point && value_axis[count] >= 0) xyz[value_axis[count]] = value;
    }
    if (count == 0) continue;
    if (count != values_per_point) {
      throw FieldError(source + ": line " + std::to_string(line_number), "expected " + std::to_string(values_per_point) +
                                                                             " values (one per FIELDS entry and COUNT), got " + std::to_string(count));
    }
    AddPoint(cloud, xyz, source + ": line " + std::to_string(line_number));
    ++read;
  }
}

// `field_start[i]` is where field i of point 0 is; `stride` how far apart two points' values are.
void ReadBinaryPoints(const std::uint8_t* data, const PcdHeader& h, const std::size_t field_start[3], std::size_t stride,
                      const std::string& where, PointCloud& cloud) {
  for (long long k = 0; k < h.points; ++k) {
    double xyz[3];
    for (int axis = 0; axis < 3; ++axis) {
      const PcdField& f = h.fields[static_cast<std::size_t>(h.xyz[axis])];
      xyz[axis] = ReadFloat(data + field_start[axis] + static_cast<std::size_t>(k) * stride, f.size);
    }
    AddPoint(cloud, xyz, where + ", point " + std::to_string(k));
  }
}

std::size_t FieldOffset(const PcdHeader& h, int field, std::size_t per_field_scale) {
  std::size_t offset = 0;
  for (int i = 0; i < field; ++i) offset += h.fields[static_cast<std::size_t>(i)].bytes() * per_field_scale;
  return offset;
}

void ReadBinary(const std::string& bytes, const PcdHeader& h, const std::string& source, PointCloud& cloud) {
  const std::string where = Line(source, h.data_line, "DATA binary");
  const std::size_t available = bytes.size() - h.data_start;
  if (static_cast<unsigned long long>(h.points) > available / h.point_bytes) {
    throw FieldError(where, "truncated binary data: POINTS " + std::to_string(h.points) + " of " + std::to_string(h.point_bytes) +
                                " bytes, but " + std::to_string(available) + " bytes follow the header");
  }
  std::size_t starts[3];
  for (int axis = 0; axis < 3; ++axis) starts[axis] = FieldOffset(h, h.xyz[axis], 1);
  ReadBinaryPoints(reinterpret_cast<const std::uint8_t*>(bytes.data()) + h.data_start, h, starts, h.point_bytes, where, cloud);
}

std::uint32_t ReadU32(const std::string& bytes, std::size_t at) {
  std::uint8_t b[4];
  std::memcpy(b, bytes.data() + at, 4);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 | static_cast<std::uint32_t>(b[2]) << 16 |
         static_cast<std::uint32_t>(b[3]) << 24;
}

// One LZF block after two little-endian sizes; decompressed, each field's values for all points
// lie together, fields in header order.
void ReadCompressed(const std::string& bytes, const PcdHeader& h, const std::string& source, PointCloud& cloud) {
  const std::string where = Line(source, h.data_line, "DATA binary_compressed");
  const std::size_t available = bytes.size() - h.data_start;
  if (available < 8) {
    throw FieldError(where, "truncated: the block's two sizes need 8 bytes, " + std::to_string(available) + " follow the header");
  }
  const std::size_t compressed = ReadU32(bytes, h.data_start), uncompressed = ReadU32(bytes, h.data_start + 4);
  if (compressed > available - 8) {
    throw FieldError(where, "truncated compressed block: " + std::to_string(compressed) + " bytes declared, " +
                                std::to_string(available - 8) + " follow");
  }
  if (static_cast<unsigned long long>(h.points) > uncompressed / h.point_bytes ||
      uncompressed != static_cast<std::size_t>(h.points) * h.point_bytes) {
    throw FieldError(where, "the block decompresses to " + std::to_string(uncompressed) + " bytes, but POINTS " +
                                std::to_string(h.points) + " of " + std::to_string(h.point_bytes) + " bytes need " +
                                std::to_string(static_cast<unsigned long long>(h.points) * h.point_bytes));
  }
  if (uncompressed / kLzfMaxExpansion > compressed) {
    throw FieldError(where, "corrupt compressed block: " + std::to_string(compressed) + " bytes cannot decompress to " +
                                std::to_string(uncompressed));
  }
  std::vector<std::uint8_t> data(uncompressed);
  const std::string problem = LzfDecompress(reinterpret_cast<const std::uint8_t*>(bytes.data()) + h.data_start + 8, compressed,
                                            data.data(), data.size());
  if (!problem.empty()) throw FieldError(where, "corrupt compressed block: " + problem);
  std::size_t starts[3];
  for (int axis = 0; axis < 3; ++axis) starts[axis] = FieldOffset(h, h.xyz[axis], static_cast<std::size_t>(h.points));
  ReadBinaryPoints(data.data(), h, starts, static_cast<std::size_t>(h.fields[static_cast<std::size_t>(h.xyz[0])].size), where,
                   cloud);
}

}  // namespace

bool LooksLikePcd(const std::string& bytes) {
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::istringstream words(bytes.substr(pos, std::min<std::size_t>(end - pos, 256)));
    pos = end + 1;
    std::string keyword;
    if (!(words >> keyword) || keyword[0] == '#') continue;
    return keyword == "VERSION" || keyword == "FIELDS";
  }
  return false;
}

PointCloud ParsePcd(const std::string& bytes, const std::string& source) {
  const PcdHeader h = ParseHeader(bytes, source);
  PointCloud cloud;
  switch (h.encoding) {
    case PcdEncoding::kAscii: ReadAscii(bytes, h, source, cloud); break;
    case PcdEncoding::kBinary: ReadBinary(bytes, h, source, cloud); break;
    case PcdEncoding::kBinaryCompressed: ReadCompressed(bytes, h, source, cloud); break;
  }
  if (cloud.empty()) {
    throw FieldError(Line(source, h.data_line, "DATA"),
                     "no finite points (all " + std::to_string(h.points) + " have a NaN coordinate)");
  }
  return cloud;
}

PointCloud ReadPcd(const std::string& path) { return ParsePcd(ReadCloudFile(path), path); }

}  // namespace stairplan
