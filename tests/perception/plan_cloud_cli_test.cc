// `stairplan plan --cloud`: plans on the stairs perceived in a point cloud and writes the fitted
// model beside the plan; a cloud with no stairs exits 3; a broken cloud exits 2 naming the file.
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "perception_scenes.h"
#include "test_paths.h"

using nlohmann::json;
using namespace stairplan;
using namespace stairplan::testing;

namespace {

std::string WriteXyz(const PointCloud& cloud, const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const auto& p : cloud.points) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  return path;
}

int PlanCloud(const std::string& cloud, const std::string& dir, std::string* err) {
  const int code = RunCommand(BinDir() + "/stairplan plan --cloud " + cloud + " --out " + dir + "/out", dir + "/o", dir + "/e");
  *err = ReadFile(dir + "/e");
  return code;
}

}  // namespace

TEST_CASE("plan --cloud plans on the perceived stairs and records the fit", "[cli][cloud]") {
  const std::string dir = MakeTempDir("plan-cloud");
  const Staircase truth{StairSpec{}};
  const Scene scene = ScanFromBottom(truth, 0.3, {1.0, -0.5, 0.0}, 0.005, 2);
  std::string err;
  const int code = PlanCloud(WriteXyz(scene.cloud, dir + "/stairs.xyz"), dir, &err);
  INFO(err);
  REQUIRE((code == 0 || code == 3));
  const json plan = json::parse(ReadFile(dir + "/out/plan.json"));
  REQUIRE(plan.contains("fitted"));
  CHECK(plan["fitted"]["steps"] == 7);
  CHECK(plan["fitted"]["rise"].get<double>() == Approx(0.17).margin(0.005));
  CHECK(plan["fitted"]["run"].get<double>() == Approx(0.27).margin(0.005));
  CHECK(plan["fitted"]["yaw_rad"].get<double>() == Approx(0.3).margin(0.02));
  CHECK(plan["stairs"]["steps"] == 7);
  CHECK(plan["status"] == "ok");
  // This scan sees every tread well enough for a step region, and the plan validates on the
  // perceived stairs (plan_from_cloud_test moves such plans onto the true stairs and validates
  // them there). Scans where occlusion leaves a tread without a step region make the crawl step
  // two stairs at once, which the validator rightly rejects (exit 3).
  REQUIRE(plan.contains("validation"));
  CHECK(code == 0);
  CHECK(plan["validation"]["ok"] == true);
  CHECK(plan["footsteps"].size() >= 24);
  for (const auto& f : plan["footsteps"]) CHECK(f["in_step_region"] == true);
}

TEST_CASE("plan --cloud of a flat floor finds no stairs and exits 3", "[cli][cloud]") {
  const std::string dir = MakeTempDir("plan-floor");
  PointCloud floor;
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 30; ++j) floor.points.emplace_back(0.05 * i, 0.05 * j - 0.75, 0.0);
  }
  std::string err;
  CHECK(PlanCloud(WriteXyz(floor, dir + "/floor.xyz"), dir, &err) == 3);
  CHECK_THAT(err, Catch::Contains("no stairs"));
}

TEST_CASE("plan --cloud with a broken cloud exits 2 naming the file", "[cli][cloud]") {
  const std::string dir = MakeTempDir("plan-cloud-bad");
  std::ofstream(dir + "/bad.xyz") << "0 0 0\n1 2\n";
  std::string err;
  CHECK(PlanCloud(dir + "/bad.xyz", dir, &err) == 2);
  CHECK_THAT(err, Catch::Contains("bad.xyz"));
}
