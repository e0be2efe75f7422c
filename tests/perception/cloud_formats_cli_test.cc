// Perception to planning through files (issue #25): the same points as PLY and as PCD in each
// encoding give `stairplan map` the same fitted stairs and constrained map; `map --stairs-out`
// writes stairs YAML that `plan --stairs` plans on and validates; `footfalls --stairs-out` writes
// one YAML per staircase walked.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stairplan/perception/footfall.h"
#include "stairplan/perception/ply_io.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "perception/footfall_scenes.h"
#include "perception/pcd_files.h"
#include "perception/perception_scenes.h"
#include "perception/path_baseline_flags.h"
#include "sanitized.h"
#include "stairplan/version.h"
#include "test_paths.h"

using namespace stairplan;
using namespace stairplan::testing;

namespace {

std::string WriteCloudFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The camera scan of the default stairs (of `steps` steps) that perception_cli_test maps, stored
// as floats.
PointCloud ScannedStairs(int steps = 7) {
  StairSpec spec;
  spec.steps = steps;
  return RoundedToFloat(ScanFromBottom(Staircase(spec), 0.4, Eigen::Vector3d(2.0, 1.0, 0.0), 0.005, 3).cloud);
}

}  // namespace

TEST_CASE("map: PCD in each encoding gives the constrained map the same points give as PLY", "[cli][perception][pcd]") {
  const std::string dir = MakeTempDir("map-pcd");
  const PointCloud cloud = ScannedStairs();
  const StairplanRun ply = RunStairplan(dir, "map --json --cloud " + WriteCloudFile(dir + "/scan.ply", PlyBytes(cloud, PlyFormat::kBinaryLittleEndian, true)));
  INFO(ply.err);
  REQUIRE(ply.code == 0);
  const nlohmann::json reference = nlohmann::json::parse(ply.out);
  REQUIRE(reference["map"]["stairs"].size() == 8u);
  PcdLayout layout;
  layout.nan_points = 25;  // pixels without a return, which the reader skips
  // Named without .pcd (and one as .xyz): the reader goes by the content.
  const struct {
    const char* name;
    PcdEncoding encoding;
  } files[] = {{"scan.pcd", PcdEncoding::kAscii}, {"scan.bin", PcdEncoding::kBinary}, {"scan.xyz", PcdEncoding::kBinaryCompressed}};
  for (const auto& f : files) {
    const StairplanRun pcd = RunStairplan(dir, "map --json --cloud " + WriteCloudFile(dir + "/" + f.name, PcdFileBytes(cloud, f.encoding, layout)));
    INFO(f.name << ": " << pcd.err);
    REQUIRE(pcd.code == 0);
    const nlohmann::json j = nlohmann::json::parse(pcd.out);
    CHECK(j["cloud"]["points"] == cloud.size());
    CHECK(j["height_map"] == reference["height_map"]);
    CHECK(j["stairs"] == reference["stairs"]);
    CHECK(j["map"] == reference["map"]);
    CHECK(j["version"] == std::string(kVersion));
    CHECK(j["schema_version"] == kSchemaVersion);
  }
}

TEST_CASE("map --stairs-out writes the stairs that plan --stairs plans on and validates", "[cli][perception][pcd]") {
  const std::string dir = MakeTempDir("map-stairs-out");
  // Under the sanitizers a 3-step flight: the plan's cost grows with the steps (tests/sanitized.h).
  const int steps = FullOrSanitized(7, 3);
  const std::string cloud = WriteCloudFile(dir + "/scan.pcd", PcdFileBytes(ScannedStairs(steps), PcdEncoding::kBinaryCompressed));
  const StairplanRun map = RunStairplan(dir, "map --cloud " + cloud + " --stairs-out " + dir + "/stairs.yaml");
  INFO(map.err);
  REQUIRE(map.code == 0);
  CHECK_THAT(map.out, Catch::Contains("wrote:      " + dir + "/stairs.yaml"));
  const StairSpec spec = StairSpecFromYamlFile(dir + "/stairs.yaml");
  CHECK(spec.steps == steps);
  CHECK(spec.rise == Approx(0.17).margin(0.005));
  CHECK(spec.run == Approx(0.27).margin(0.005));
  CHECK(spec.direction == TravelDirection::kUp);
  const StairplanRun plan = RunStairplan(dir, "plan --stairs " + dir + "/stairs.yaml --out " + dir + "/plan");
  INFO(plan.out << plan.err);
  CHECK(plan.code == 0);
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir + "/plan/plan.json"));
  CHECK(j["status"] == "ok");
  CHECK(j["validation"]["ok"] == true);
  CHECK(j["stairs"]["steps"] == steps);
  CHECK(j["stairs"]["rise"].get<double>() == spec.rise);
  // A cloud that is not stairs exits 3 and writes no YAML.
  PointCloud floor;
  for (int i = 0; i < 40; ++i) {
    for (int k = 0; k < 20; ++k) floor.points.emplace_back(0.05 * i, 0.05 * k, 0.0);
  }
  const StairplanRun flat = RunStairplan(dir, "map --cloud " + WriteCloudFile(dir + "/floor.pcd", PcdFileBytes(floor, PcdEncoding::kBinary)) +
                                         " --stairs-out " + dir + "/floor.yaml");
  CHECK(flat.code == 3);
  CHECK_FALSE(std::filesystem::exists(dir + "/floor.yaml"));
}

TEST_CASE("footfalls --stairs-out writes one stairs YAML per staircase walked", "[cli][perception]") {
  const std::string dir = MakeTempDir("footfalls-stairs-out");
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  const std::string csv = WriteCloudFile(dir + "/walk.csv", FootfallCsv(WalkFootfalls(TwoUpTwoDownLoop(), walk)));
  const StairplanRun o = RunStairplan(dir, "footfalls " + csv + " --json --stairs-out " + dir + "/flight.yaml");
  INFO(o.err);
  REQUIRE(o.code == 0);
  const nlohmann::json j = nlohmann::json::parse(o.out);
  CHECK(j["version"] == std::string(kVersion));
  const auto& staircases = j["staircases"];
  REQUIRE(staircases.size() == 4u);
  const char* files[4] = {"flight.yaml", "flight_1.yaml", "flight_2.yaml", "flight_3.yaml"};
  for (std::size_t i = 0; i < 4; ++i) {
    INFO(files[i]);
    CHECK(j["stairs_out"][i] == dir + "/" + files[i]);
    const StairSpec spec = StairSpecFromYamlFile(dir + "/" + files[i]);
    CHECK(spec.steps == staircases[i]["steps"]);
    CHECK(spec.rise == staircases[i]["rise"].get<double>());
    CHECK(spec.run == staircases[i]["run"].get<double>());
    CHECK(ToString(spec.direction) == staircases[i]["traversal"].get<std::string>());
  }
  CHECK_FALSE(std::filesystem::exists(dir + "/flight_4.yaml"));
}

TEST_CASE("map --stairs-out: plans on the perceived stairs keep the fit's uncertainty and validate on the true stairs", "[cli][perception][pcd]") {
  const std::string dir = MakeTempDir("map-true-stairs");
  // Scanned in the stairs' own frame and without a nosing, so that the true stairs YAML and the
  // fitted one (origin at the first edge, nosing 0) share their frame up to the fit's error.
  StairSpec spec;
  spec.steps = FullOrSanitized(7, 3);
  spec.nosing = 0.0;
  const Staircase truth(spec);
  const PointCloud cloud = RoundedToFloat(ScanFromBottom(truth, 0.0, Eigen::Vector3d::Zero(), 0.005, 3).cloud);
  const std::string scan = WriteCloudFile(dir + "/scan.pcd", PcdFileBytes(cloud, PcdEncoding::kBinary));
  std::ofstream(dir + "/true.yaml") << StairSpecToYaml(spec);
  const StairplanRun map = RunStairplan(dir, "map --cloud " + scan + " --stairs-out " + dir + "/stairs.yaml");
  INFO(map.out << map.err);
  REQUIRE(map.code == 0);
  const StairSpec seen = StairSpecFromYamlFile(dir + "/stairs.yaml");
  CHECK(seen.uncertainty > 0.0);
  CHECK(seen.uncertainty < 0.03);
  // The default and the quasi-static path baseline; under the sanitizers the default only (as
  // "footfalls --stairs-out, plan --stairs: ...").
  std::vector<std::string> bodies = {std::string()};
  if (!kSanitized) bodies.push_back(std::string(kPathBaseline));
  for (const std::string& body : bodies) {
    INFO((body.empty() ? "default" : "path baseline"));
    const std::string out = dir + (body.empty() ? "/plan" : "/plan_path");
    const StairplanRun plan = RunStairplan(dir, "plan --stairs " + dir + "/stairs.yaml " + body + " --out " + out);
    INFO(plan.out << plan.err);
    REQUIRE(plan.code == 0);
    const nlohmann::json j = nlohmann::json::parse(ReadFile(out + "/plan.json"));
    CHECK(j["clearance"]["stairs_uncertainty_m"].get<double>() == seen.uncertainty);
    CHECK(j["stairs"]["uncertainty"].get<double>() == seen.uncertainty);
    const StairplanRun valid = RunStairplan(dir, "validate " + out + "/plan.json --stairs " + dir + "/true.yaml");
    INFO(valid.out << valid.err);
    CHECK(valid.code == 0);
  }
}

TEST_CASE("stairs YAML: the uncertainty is optional, and a bad one exits 2 naming the file and field", "[cli][perception]") {
  const std::string dir = MakeTempDir("stairs-uncertainty");
  StairSpec spec;
  spec.uncertainty = 0.004;
  CHECK(StairSpecFromYaml(StairSpecToYaml(spec), "round trip").uncertainty == 0.004);
  CHECK(StairSpecFromYaml("steps: 3\n", "old file").uncertainty == 0.0);
  CHECK(StairSpecToYaml(StairSpec{}).find("uncertainty") == std::string::npos);
  for (const char* bad : {"-0.001", "0.5", "nan", "[1]"}) {
    std::ofstream(dir + "/bad.yaml") << "steps: 3\nuncertainty: " << bad << "\n";
    const StairplanRun plan = RunStairplan(dir, "plan --stairs " + dir + "/bad.yaml --out " + dir + "/out");
    INFO(bad << ": " << plan.err);
    CHECK(plan.code == 2);
    CHECK_THAT(plan.err, Catch::Contains(dir + "/bad.yaml") && Catch::Contains("uncertainty"));
  }
}
