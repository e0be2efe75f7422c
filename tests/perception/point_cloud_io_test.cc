// Point-cloud readers: PLY (ascii, binary little-endian, float and double) and XYZ text round-trip
// exactly enough, and broken files are errors that name the file and the line (or vertex).
#include <catch2/catch.hpp>

#include <fstream>
#include <random>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/ply_io.h"
#include "stairplan/perception/point_cloud.h"
#include "stairplan/perception/xyz_io.h"
#include "test_paths.h"

using namespace stairplan;

namespace {

PointCloud RandomCloud(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  PointCloud cloud;
  for (int i = 0; i < n; ++i) cloud.points.emplace_back(u(rng), u(rng), u(rng));
  return cloud;
}

double MaxError(const PointCloud& a, const PointCloud& b) {
  REQUIRE(a.size() == b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a.points[i] - b.points[i]).cwiseAbs().maxCoeff());
  return worst;
}

std::string WriteTemp(const std::string& name, const std::string& contents) {
  const std::string path = stairplan::testing::MakeTempDir("cloud") + "/" + name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

// The message of the FieldError the reader throws, or "" when it does not throw.
template <typename Fn>
std::string ErrorOf(Fn fn) {
  try {
    fn();
  } catch (const FieldError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("PLY round trips in ascii and binary, float and double", "[cloud]") {
  const PointCloud cloud = RandomCloud(500, 3);
  for (PlyFormat format : {PlyFormat::kAscii, PlyFormat::kBinaryLittleEndian}) {
    CHECK(MaxError(ParsePly(PlyBytes(cloud, format), "mem"), cloud) < 1e-9);
    // Floats keep about seven significant digits: 5 m * 2^-23 is well under a micrometre.
    CHECK(MaxError(ParsePly(PlyBytes(cloud, format, true), "mem"), cloud) < 1e-6);
  }
  const std::string path = WriteTemp("cloud.ply", PlyBytes(cloud, PlyFormat::kBinaryLittleEndian));
  CHECK(MaxError(ReadPointCloud(path), cloud) < 1e-9);
}

TEST_CASE("PLY skips extra vertex properties and elements after the vertices", "[cloud]") {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property uchar red\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "1 2 255 3\n4 5 0 6\n3 0 1 1\n";
  const PointCloud cloud = ParsePly(text, "hand.ply");
  REQUIRE(cloud.size() == 2);
  CHECK(cloud.points[1].isApprox(Eigen::Vector3d(4, 5, 6)));
}

TEST_CASE("XYZ text round trips and skips comments and extra columns", "[cloud]") {
  const PointCloud cloud = RandomCloud(200, 5);
  CHECK(MaxError(ParseXyz(XyzText(cloud), "mem"), cloud) < 1e-7);
  const PointCloud extra = ParseXyz("# x y z r g b\n\n1 2 3 9 9 9\n  4 5 6\n", "mem");
  REQUIRE(extra.size() == 2);
  CHECK(extra.points[0].isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST_CASE("truncated ascii PLY names the file and the line where data ran out", "[cloud][errors]") {
  std::string text = PlyBytes(RandomCloud(10, 1), PlyFormat::kAscii);
  // Cut the last three vertex lines: the header is 8 lines, vertices are lines 9-18.
  for (int i = 0; i < 3; ++i) text.erase(text.rfind('\n', text.size() - 2) + 1);
  const std::string message = ErrorOf([&] { ParsePly(text, "cut.ply"); });
  CHECK_THAT(message, Catch::Contains("cut.ply: line 16"));
  CHECK_THAT(message, Catch::Contains("7 of 10"));
}

TEST_CASE("binary PLY elements before the vertices are skipped whole, however many they declare", "[cloud]") {
  // An element of no bytes declared 4e18 times once took that many loop turns (found by the fuzzer).
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement marker 4000000000000000000\n";
  const float xyz[3] = {1.0f, 2.0f, 3.0f};
  const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n" +
                             std::string(reinterpret_cast<const char*>(xyz), sizeof(xyz));
  const PointCloud cloud = ParsePly(header + vertex, "marker.ply");
  REQUIRE(cloud.size() == 1);
  CHECK(cloud.points[0].isApprox(Eigen::Vector3d(1, 2, 3)));
  // With bytes per entry, the declared count must fit in the file.
  const std::string sized = "ply\nformat binary_little_endian 1.0\nelement blob 4000000000000000000\nproperty uchar b\n";
  CHECK_THAT(ErrorOf([&] { ParsePly(sized + vertex, "blob.ply"); }), Catch::Contains("blob.ply: blob"));
}

TEST_CASE("truncated binary PLY names the file and the vertex", "[cloud][errors]") {
  std::string bytes = PlyBytes(RandomCloud(10, 1), PlyFormat::kBinaryLittleEndian);
  bytes.resize(bytes.size() - 30);  // vertex 9 loses most of its 24 bytes, vertex 8 a little
  const std::string message = ErrorOf([&] { ParsePly(bytes, "cut.ply"); });
  CHECK_THAT(message, Catch::Contains("cut.ply: vertex 8"));
  CHECK_THAT(message, Catch::Contains("truncated"));
}

TEST_CASE("NaN coordinates are errors naming the line or vertex", "[cloud][errors]") {
  const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                           "end_header\n0 0 0\n1 nan 1\n2 2 2\n";
  CHECK_THAT(ErrorOf([&] { ParsePly(text, "nan.ply"); }), Catch::Contains("nan.ply: line 9"));
  PointCloud cloud = RandomCloud(4, 2);
  cloud.points[2].z() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(ErrorOf([&] { ParsePly(PlyBytes(cloud, PlyFormat::kBinaryLittleEndian), "nan.ply"); }),
             Catch::Contains("nan.ply: vertex 2"));
  CHECK_THAT(ErrorOf([&] { ParseXyz("1 2 3\n4 inf 6\n", "pts.xyz"); }), Catch::Contains("pts.xyz: line 2"));
}

TEST_CASE("empty files, bad rows and missing files are errors naming the file", "[cloud][errors]") {
  CHECK_THAT(ErrorOf([] { ParsePly("", "empty.ply"); }), Catch::Contains("empty.ply: line 1"));
  CHECK_THAT(ErrorOf([] { ParseXyz("", "empty.xyz"); }), Catch::Contains("empty.xyz"));
  CHECK_THAT(ErrorOf([] { ParseXyz("1 2 3\n4 five 6\n", "bad.xyz"); }), Catch::Contains("bad.xyz: line 2"));
  CHECK_THAT(ErrorOf([] { ParseXyz("1 2 3\n4 5\n", "short.xyz"); }), Catch::Contains("short.xyz: line 2"));
  CHECK_THAT(ErrorOf([] { ParsePly("ply\nformat binary_big_endian 1.0\nend_header\n", "be.ply"); }),
             Catch::Contains("be.ply: line 2"));
  CHECK_THAT(ErrorOf([] { ParsePly("ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\n", "int.ply"); }),
             Catch::Contains("int.ply: line 4"));
  CHECK_THAT(ErrorOf([] { ReadPointCloud("/nonexistent/dir/cloud.ply"); }), Catch::Contains("/nonexistent/dir/cloud.ply"));
}
