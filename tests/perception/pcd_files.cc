#include "perception/pcd_files.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace stairplan::testing {

std::string LzfCompress(const std::string& in) {
  std::string out;
  std::unordered_map<std::uint32_t, std::size_t> last;  // 3 bytes -> where they last began
  std::size_t literal_start = 0, i = 0;
  const auto flush_literals = [&](std::size_t end) {
    while (literal_start < end) {
      const std::size_t run = std::min<std::size_t>(32, end - literal_start);
      out.push_back(static_cast<char>(run - 1));
      out.append(in, literal_start, run);
      literal_start += run;
    }
  };
  const auto byte = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(in[k])); };
  while (i + 2 < in.size()) {
    const std::uint32_t key = byte(i) | byte(i + 1) << 8 | byte(i + 2) << 16;
    const auto found = last.find(key);
    const std::size_t candidate = found == last.end() ? i : found->second;
    last[key] = i;
    if (candidate < i && i - candidate <= 8192) {
      const std::size_t max_length = std::min<std::size_t>(264, in.size() - i);
      std::size_t length = 0;
      while (length < max_length && in[candidate + length] == in[i + length]) ++length;
      if (length >= 3) {
        flush_literals(i);
        const std::size_t offset = i - candidate - 1, code = length - 2;
        out.push_back(static_cast<char>((std::min<std::size_t>(code, 7) << 5) | (offset >> 8)));
        if (code >= 7) out.push_back(static_cast<char>(code - 7));
        out.push_back(static_cast<char>(offset & 0xff));
        i += length;
        literal_start = i;
        continue;
      }
    }
    ++i;
  }
  flush_literals(in.size());
  return out;
}

namespace {

struct TestField {
  std::string name;
  int size;
  char type;
};

std::vector<TestField> Fields(const PcdLayout& layout) {
  const int xyz = layout.xyz_double ? 8 : 4;
  std::vector<TestField> fields;
  if (layout.label_first) fields.push_back({"label", 1, 'U'});
  for (const char* axis : {"x", "y", "z"}) fields.push_back({axis, xyz, 'F'});
  fields.push_back({"rgb", 4, 'U'});
  return fields;
}

// The bytes of one field of one point (NaN coordinates past the cloud's points).
std::string FieldBytes(const TestField& f, const PointCloud& cloud, std::size_t k) {
  const int axis = f.name == "x" ? 0 : f.name == "y" ? 1 : f.name == "z" ? 2 : -1;
  std::string bytes(static_cast<std::size_t>(f.size), '\0');
  if (axis < 0) {
    const std::uint32_t value = static_cast<std::uint32_t>(k * 2654435761u);  // any bits: ignored
    std::memcpy(&bytes[0], &value, static_cast<std::size_t>(f.size));
    return bytes;
  }
  const double v = k < cloud.size() ? cloud.points[k][axis] : std::numeric_limits<double>::quiet_NaN();
  if (f.size == 4) {
    const float single = static_cast<float>(v);
    std::memcpy(&bytes[0], &single, 4);
  } else {
    std::memcpy(&bytes[0], &v, 8);
  }
  return bytes;
}

}  // namespace

std::string PcdFileBytes(const PointCloud& cloud, PcdEncoding encoding, const PcdLayout& layout) {
  const std::vector<TestField> fields = Fields(layout);
  const std::size_t n = cloud.size() + static_cast<std::size_t>(layout.nan_points);
  std::ostringstream out;
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS";
  for (const auto& f : fields) out << " " << f.name;
  out << "\nSIZE";
  for (const auto& f : fields) out << " " << f.size;
  out << "\nTYPE";
  for (const auto& f : fields) out << " " << f.type;
  out << "\nCOUNT";
  for (std::size_t i = 0; i < fields.size(); ++i) out << " 1";
  out << "\nWIDTH " << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA "
      << (encoding == PcdEncoding::kAscii ? "ascii" : encoding == PcdEncoding::kBinary ? "binary" : "binary_compressed") << "\n";
  if (encoding == PcdEncoding::kAscii) {
    out.precision(17);  // the exact double of each stored value
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string bytes = FieldBytes(fields[i], cloud, k);
        if (i) out << " ";
        if (fields[i].type == 'U') {
          std::uint32_t value = 0;
          std::memcpy(&value, bytes.data(), bytes.size());
          out << value;
        } else if (fields[i].size == 4) {
          float value;
          std::memcpy(&value, bytes.data(), 4);
          out << static_cast<double>(value);
        } else {
          double value;
          std::memcpy(&value, bytes.data(), 8);
          out << value;
        }
      }
      out << "\n";
    }
  } else if (encoding == PcdEncoding::kBinary) {
    for (std::size_t k = 0; k < n; ++k) {
      for (const auto& f : fields) out << FieldBytes(f, cloud, k);
    }
  } else {
    std::string data;  // field after field, as PCL stores a compressed block
    for (const auto& f : fields) {
      for (std::size_t k = 0; k < n; ++k) data += FieldBytes(f, cloud, k);
    }
    const std::string compressed = LzfCompress(data);
    const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(compressed.size()), static_cast<std::uint32_t>(data.size())};
    out.write(reinterpret_cast<const char*>(sizes), sizeof sizes);
    out << compressed;
  }
  return out.str();
}

PointCloud RoundedToFloat(const PointCloud& cloud) {
  PointCloud out = cloud;
  for (auto& p : out.points) p = p.cast<float>().cast<double>();
  return out;
}

}  // namespace stairplan::testing
