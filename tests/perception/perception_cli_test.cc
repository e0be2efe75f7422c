// `stairplan map` and `stairplan footfalls`: JSON on synthetic data, and bad files (truncated or
// NaN-laden PLY, an empty file, a CSV with a bad row) exit 2 naming the file and the line.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "stairplan/perception/footfall.h"
#include "stairplan/perception/ply_io.h"
#include "stairplan/perception/xyz_io.h"
#include "perception/footfall_scenes.h"
#include "perception/perception_scenes.h"
#include "test_paths.h"

using namespace stairplan;
using stairplan::testing::MakeTempDir;
using stairplan::testing::ReadFile;
using stairplan::testing::RunStairplan;
using stairplan::testing::StairplanRun;

namespace {

std::string Write(const std::string& dir, const std::string& name, const std::string& contents) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

}  // namespace

TEST_CASE("stairplan map: fitted stairs and the constrained map of a camera cloud", "[cli][perception]") {
  const std::string dir = MakeTempDir("map");
  const double yaw = 0.4;
  const auto scene = stairplan::testing::ScanFromBottom(Staircase(StairSpec{}), yaw, Eigen::Vector3d(2.0, 1.0, 0.0), 0.005, 3);
  const std::string cloud = Write(dir, "stairs.ply", PlyBytes(scene.cloud, PlyFormat::kBinaryLittleEndian, true));
  const StairplanRun r = RunStairplan(dir, "map --cloud " + cloud + " --json --svg " + dir + "/map.svg");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto json = nlohmann::json::parse(r.out);
  CHECK(json["cloud"]["points"] == scene.cloud.size());
  const auto& stairs = json["stairs"];
  CHECK(stairs["steps"] == 7);
  CHECK(std::abs(stairs["rise"].get<double>() - 0.17) <= 0.005);
  CHECK(std::abs(stairs["run"].get<double>() - 0.27) <= 0.005);
  CHECK(std::abs(std::remainder(stairs["yaw_rad"].get<double>() - yaw, 2.0 * M_PI)) <= M_PI / 180.0);
  CHECK(json["map"]["stairs"].size() == 8u);
  CHECK(json["height_map"]["occluded"].get<int>() > 0);
  CHECK_THAT(ReadFile(dir + "/map.svg"), Catch::StartsWith("<svg"));
  // The summary names the same stairs.
  const StairplanRun text = RunStairplan(dir, "map --cloud " + cloud + " --direction down --facing backward");
  CHECK(text.code == 0);
  CHECK_THAT(text.out, Catch::Contains("7 steps"));
}

TEST_CASE("stairplan map: a flat floor is not stairs (exit 3, stairs null)", "[cli][perception]") {
  const std::string dir = MakeTempDir("map-flat");
  PointCloud floor;
  for (double x = 0.0; x < 2.0; x += 0.02) {
    for (double y = -0.5; y < 0.5; y += 0.02) floor.points.emplace_back(x, y, 0.001 * std::sin(37.0 * x * y));
  }
  const std::string cloud = Write(dir, "floor.xyz", XyzText(floor));
  const StairplanRun r = RunStairplan(dir, "map --cloud " + cloud + " --json");
  REQUIRE(r.code == 3);
  const auto json = nlohmann::json::parse(r.out);
  CHECK(json["stairs"].is_null());
  CHECK_THAT(json["reason"].get<std::string>(), Catch::Contains("flat"));
}

TEST_CASE("stairplan map: bad clouds exit 2 naming the file and the line", "[cli][perception][errors]") {
  const std::string dir = MakeTempDir("map-bad");
  PointCloud cloud;
  for (int i = 0; i < 20; ++i) cloud.points.emplace_back(0.1 * i, 0.0, 0.0);
  std::string truncated = PlyBytes(cloud, PlyFormat::kAscii);
  truncated.resize(truncated.size() - 40);  // the last vertex lines are gone, one is cut short
  std::string nan = PlyBytes(cloud, PlyFormat::kAscii);
  nan.replace(nan.find("\n0.4 0 0\n") + 1, 7, "0.4 nan 0");
  const struct {
    std::string name, contents, expected;
  } cases[] = {
      {"truncated.ply", truncated, "truncated.ply: line "},
      {"nan.ply", nan, "nan.ply: line 13"},
      {"empty.ply", "", "empty.ply: line 1"},
      {"empty.xyz", "", "empty.xyz: line 1"},
      {"bad_row.xyz", "0 0 0\n1 0 0\n1 zero 0\n", "bad_row.xyz: line 3"},
  };
  for (const auto& c : cases) {
    const std::string path = Write(dir, c.name, c.contents);
    const StairplanRun r = RunStairplan(dir, "map --cloud " + path);
    INFO(c.name << ": " << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(dir + "/" + c.expected));
  }
  CHECK(RunStairplan(dir, "map --cloud " + dir + "/missing.ply").code == 2);
  CHECK(RunStairplan(dir, "map").code == 2);
  CHECK(RunStairplan(dir, "map --cloud " + dir + "/bad_row.xyz --direction sideways").code == 2);
}

TEST_CASE("stairplan footfalls: the loop's four staircases as JSON", "[cli][perception]") {
  const std::string dir = MakeTempDir("footfalls");
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  const std::string csv = Write(dir, "walk.csv", FootfallCsv(WalkFootfalls(stairplan::testing::TwoUpTwoDownLoop(), walk)));
  const StairplanRun r = RunStairplan(dir, "footfalls " + csv + " --json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto json = nlohmann::json::parse(r.out);
  const auto& staircases = json["staircases"];
  REQUIRE(staircases.size() == 4u);
  const int steps[4] = {6, 5, 6, 5};
  const char* traversal[4] = {"up", "up", "down", "down"};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(staircases[i]["steps"] == steps[i]);
    CHECK(staircases[i]["traversal"] == traversal[i]);
    CHECK(staircases[i]["edges"].size() == static_cast<std::size_t>(steps[i]));
    CHECK(staircases[i]["rise"].get<double>() > 0.14);
    CHECK(staircases[i]["run"].get<double>() > 0.25);
    CHECK(staircases[i]["direction"].size() == 2u);
  }
  const StairplanRun text = RunStairplan(dir, "footfalls " + csv);
  CHECK(text.code == 0);
  CHECK_THAT(text.out, Catch::Contains("4 staircases"));
}

TEST_CASE("stairplan footfalls: a CSV with a bad row exits 2 naming the file and the line", "[cli][perception][errors]") {
  const std::string dir = MakeTempDir("footfalls-bad");
  const std::string csv = Write(dir, "bad.csv", "t,leg,x,y,z\n0,LF,0,0,0\n0.5,RF,0,0.3\n");
  const StairplanRun r = RunStairplan(dir, "footfalls " + csv);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(csv + ": line 3"));
  const StairplanRun empty = RunStairplan(dir, "footfalls " + Write(dir, "empty.csv", ""));
  CHECK(empty.code == 2);
  CHECK_THAT(empty.err, Catch::Contains("empty.csv: line 1"));
  CHECK(RunStairplan(dir, "footfalls " + dir + "/missing.csv").code == 2);
  CHECK(RunStairplan(dir, "footfalls " + csv + " --min-rise -1").code == 2);
}
