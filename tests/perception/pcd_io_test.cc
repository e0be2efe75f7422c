// PCD clouds: the three encodings read back the exact points PCL's layouts store (fields before
// and after x y z, float and double, points without a return skipped), the LZF decoder against
// known streams and our compressor's, the format chosen by content, and broken files refused
// naming the file and the header field or the DATA encoding.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/lzf.h"
#include "stairplan/perception/pcd_io.h"
#include "stairplan/perception/ply_io.h"
#include "stairplan/perception/point_cloud.h"
#include "perception/pcd_files.h"
#include "test_paths.h"

using namespace stairplan;
using stairplan::testing::LzfCompress;
using stairplan::testing::PcdFileBytes;
using stairplan::testing::PcdLayout;

namespace {

PointCloud PcdTestCloud(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  PointCloud cloud;
  for (int i = 0; i < n; ++i) cloud.points.emplace_back(u(rng), u(rng), 0.17 * (i % 7));  // repeated z: back references
  return cloud;
}

bool SamePcdPoints(const PointCloud& a, const PointCloud& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a.points[i] != b.points[i]) return false;
  }
  return true;
}

std::string LzfDecode(const std::string& in, std::size_t out_size, std::string* problem) {
  std::string out(out_size, '\0');
  *problem = LzfDecompress(reinterpret_cast<const std::uint8_t*>(in.data()), in.size(), reinterpret_cast<std::uint8_t*>(&out[0]),
                           out.size());
  return out;
}

std::string PcdError(const std::string& bytes, const std::string& source) {
  try {
    ParsePcd(bytes, source);
  } catch (const FieldError& e) {
    return e.what();
  }
  return "";
}

const PcdEncoding kPcdEncodings[] = {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed};

}  // namespace

TEST_CASE("LZF: a literal run and an overlapping back reference, and corrupt streams", "[cloud][pcd]") {
  std::string problem;
  // "abc", then 9 bytes from 3 back: the reference overlaps what it writes.
  const std::string stream = std::string("\x02" "abc" "\xe0\x00\x02", 7);
  CHECK(LzfDecode(stream, 12, &problem) == "abcabcabcabc");
  CHECK(problem.empty());
  LzfDecode(std::string("\x20\x05", 2), 4, &problem);
  CHECK_THAT(problem, Catch::Contains("before the start"));
  LzfDecode(std::string("\x05" "ab", 3), 6, &problem);
  CHECK_THAT(problem, Catch::Contains("past the end"));
  LzfDecode(stream, 11, &problem);  // more than declared
  CHECK_THAT(problem, Catch::Contains("declared"));
  LzfDecode(stream, 13, &problem);  // less than declared
  CHECK_THAT(problem, Catch::Contains("12 of the declared 13"));
  LzfDecode(std::string("\x02" "abc" "\xe0", 5), 12, &problem);
  CHECK_THAT(problem, Catch::Contains("cut off"));
}

TEST_CASE("LZF: our compressor's streams decode to their input and use back references", "[cloud][pcd]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t size = std::uniform_int_distribution<std::size_t>(0, 20000)(rng);
    const int alphabet = 1 + trial % 5;  // small alphabets repeat, so references of every length occur
    std::string input(size, '\0');
    for (char& c : input) c = static_cast<char>('a' + std::uniform_int_distribution<int>(0, alphabet - 1)(rng));
    const std::string compressed = LzfCompress(input);
    std::string problem;
    INFO("trial " << trial << ", " << size << " bytes");
    CHECK(LzfDecode(compressed, input.size(), &problem) == input);
    CHECK(problem.empty());
    if (size > 1000 && alphabet == 1) CHECK(compressed.size() < input.size() / 50);  // runs of 264 bytes in 3
    if (size > 1000 && alphabet == 2) CHECK(compressed.size() < input.size() * 3 / 4);
  }
}

TEST_CASE("PCD: ascii, binary and binary_compressed give the stored points exactly", "[cloud][pcd]") {
  const PointCloud cloud = PcdTestCloud(3000, 5);
  const PointCloud floats = stairplan::testing::RoundedToFloat(cloud);
  for (const PcdEncoding encoding : kPcdEncodings) {
    for (const bool label_first : {false, true}) {
      for (const bool xyz_double : {false, true}) {
        PcdLayout layout;
        layout.label_first = label_first;
        layout.xyz_double = xyz_double;
        layout.nan_points = 17;
        INFO("encoding " << static_cast<int>(encoding) << ", label first " << label_first << ", double " << xyz_double);
        const std::string bytes = PcdFileBytes(cloud, encoding, layout);
        CHECK(LooksLikePcd(bytes));
        // The NaN points (no return) are skipped; the others are what the file stores.
        CHECK(SamePcdPoints(ParsePcd(bytes, "mem.pcd"), xyz_double ? cloud : floats));
      }
    }
  }
}

TEST_CASE("Clouds are read by their content, whatever the extension", "[cloud][pcd]") {
  const PointCloud cloud = stairplan::testing::RoundedToFloat(PcdTestCloud(200, 6));
  const std::string dir = stairplan::testing::MakeTempDir("cloud-content");
  const struct {
    std::string name, bytes;
    CloudFormat format;
  } files[] = {
      {"scan.xyz", PcdFileBytes(cloud, PcdEncoding::kBinaryCompressed), CloudFormat::kPcd},
      {"scan", PcdFileBytes(cloud, PcdEncoding::kAscii), CloudFormat::kPcd},
      {"scan.txt", PlyBytes(cloud, PlyFormat::kBinaryLittleEndian, true), CloudFormat::kPly},
      {"scan.pcd", PcdFileBytes(cloud, PcdEncoding::kBinary), CloudFormat::kPcd},
  };
  for (const auto& f : files) {
    INFO(f.name);
    CHECK(DetectCloudFormat(f.bytes, f.name) == f.format);
    std::ofstream(dir + "/" + f.name, std::ios::binary) << f.bytes;
    CHECK(SamePcdPoints(ReadPointCloud(dir + "/" + f.name), cloud));
  }
  // A .pcd that is not PCD gets the PCD reader's error, naming the file.
  std::ofstream(dir + "/text.pcd") << "0 0 0\n1 0 0\n";
  CHECK(DetectCloudFormat("0 0 0\n", "text.pcd") == CloudFormat::kPcd);
  CHECK_THROWS_WITH(ReadPointCloud(dir + "/text.pcd"), Catch::Contains(dir + "/text.pcd") && Catch::Contains("header"));
  CHECK(DetectCloudFormat("# comment\n0 0 0\n", "c.txt") == CloudFormat::kXyz);
}

TEST_CASE("PCD: broken files name the file and the header field or the encoding", "[cloud][pcd][errors]") {
  const PointCloud cloud = PcdTestCloud(50, 7);
  const std::string ascii = PcdFileBytes(cloud, PcdEncoding::kAscii);
  const std::string binary = PcdFileBytes(cloud, PcdEncoding::kBinary);
  const std::string compressed = PcdFileBytes(cloud, PcdEncoding::kBinaryCompressed);
  const auto edit = [](std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
  };
  const std::size_t block = compressed.find("binary_compressed\n") + 18;  // the two sizes, then LZF
  std::string corrupt = compressed;
  corrupt[block + 8] = '\x3f';  // the first control byte: a back reference before any output
  std::string short_ascii = ascii;  // the last three rows gone
  for (int k = 0; k < 3; ++k) short_ascii.erase(short_ascii.rfind('\n', short_ascii.size() - 2) + 1);
  std::string short_block = compressed;
  const std::uint32_t bigger = static_cast<std::uint32_t>(50 * 16 + 4);
  std::memcpy(&short_block[block + 4], &bigger, 4);
  const struct {
    std::string label, bytes;
    std::vector<std::string> names;
  } cases[] = {
      {"wrong field count", edit(ascii, "SIZE 4 4 4 4", "SIZE 4 4 4"), {"c.pcd: line 4 (SIZE)", "3 entries, FIELDS names 4"}},
      {"wrong type count", edit(ascii, "TYPE F F F U", "TYPE F F F U U"), {"(TYPE)", "5 entries"}},
      {"huge count", edit(ascii, "COUNT 1 1 1 1", "COUNT 1 1 1 65536"), {"(FIELDS)", "65539 values", "at most 65536"}},
      {"no z", edit(ascii, "FIELDS x y z rgb", "FIELDS x y w rgb"), {"(FIELDS)", "x, y and z"}},
      {"integer x", edit(ascii, "TYPE F F F U", "TYPE I F F U"), {"field 'x'", "TYPE F"}},
      {"points vs width", edit(ascii, "POINTS 50", "POINTS 49"), {"(POINTS)", "WIDTH x HEIGHT"}},
      {"short ascii", short_ascii, {"(POINTS)", "47 of 50 points"}},
      {"truncated binary", binary.substr(0, binary.size() - 5), {"(DATA binary)", "truncated", "POINTS 50"}},
      {"corrupt compressed block", corrupt, {"(DATA binary_compressed)", "corrupt compressed block", "before the start"}},
      {"size mismatch", short_block, {"(DATA binary_compressed)", "POINTS 50"}},
      {"truncated block", compressed.substr(0, compressed.size() - 3), {"(DATA binary_compressed)", "truncated compressed block"}},
      {"no sizes", compressed.substr(0, block + 5), {"(DATA binary_compressed)", "8 bytes"}},
      {"unknown encoding", edit(ascii, "DATA ascii", "DATA lzma"), {"(DATA)", "lzma"}},
      {"no data line", ascii.substr(0, ascii.find("DATA")), {"no DATA line"}},
      {"unknown keyword", edit(ascii, "HEIGHT 1", "HIGHT 1"), {"line 8 (HIGHT)"}},
      {"empty", "", {"c.pcd: line 1", "empty"}},
      {"all NaN", PcdFileBytes(PointCloud{}, PcdEncoding::kBinary, PcdLayout{false, false, 3}), {"no finite points"}},
      {"zero points", edit(edit(ascii, "POINTS 50", "POINTS 0"), "WIDTH 50", "WIDTH 0"), {"(POINTS)", "no points"}},
  };
  for (const auto& c : cases) {
    INFO(c.label);
    const std::string message = PcdError(c.bytes, "c.pcd");
    CHECK_THAT(message, Catch::StartsWith("c.pcd"));
    for (const std::string& name : c.names) CHECK_THAT(message, Catch::Contains(name));
  }
  // A row with a value missing names its line; an infinite coordinate names its point.
  std::string rows = ascii;
  const std::size_t first_row = rows.find("DATA ascii\n") + 11;
  rows.replace(first_row, rows.find('\n', first_row) - first_row, "1 2 3");
  CHECK_THAT(PcdError(rows, "c.pcd"), Catch::Contains("c.pcd: line 12") && Catch::Contains("expected 4 values"));
  std::string infinite = ascii;
  infinite.replace(first_row, infinite.find('\n', first_row) - first_row, "1 inf 3 0");
  CHECK_THAT(PcdError(infinite, "c.pcd"), Catch::Contains("c.pcd: line 12") && Catch::Contains("infinite y"));
  // A huge POINTS in a small binary file is refused before anything is allocated.
  CHECK_THAT(PcdError(edit(edit(binary, "POINTS 50", "POINTS 4000000000"), "WIDTH 50", "WIDTH 4000000000"), "c.pcd"),
             Catch::Contains("truncated"));
  CHECK_THAT(PcdError(edit(edit(compressed, "POINTS 50", "POINTS 4000000000"), "WIDTH 50", "WIDTH 4000000000"), "c.pcd"),
             Catch::Contains("POINTS 4000000000"));
}
