// Footfalls to plans through files (issue #26, acceptance 4): the footfall log of the four-flight
// loop the perception tests walk gives stairs YAML (`footfalls --stairs-out`), `plan --stairs`
// plans each flight on what the footfalls found, and `validate --stairs` replays each plan on the
// flight's true stairs. The footfalls find the walking edges but not the nosing under them: the
// user gives it (--nosing, the loop's 2 cm); without it a plan's shank meets a nosing going down.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stairplan/perception/footfall.h"
#include "stairplan/geometry/stair_mode.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "perception/footfall_scenes.h"
#include "perception/path_baseline_flags.h"
#include "sanitized.h"
#include "test_paths.h"

using namespace stairplan;
using namespace stairplan::testing;


TEST_CASE("footfalls --stairs-out, plan --stairs: plans that validate on the true stairs", "[cli][perception][footfalls]") {
  const std::string dir = MakeTempDir("footfalls-plan");
  const std::vector<PlacedFlight> loop = TwoUpTwoDownLoop();
  FootfallWalkSettings walk;
  walk.sigma = 0.01;
  std::ofstream(dir + "/walk.csv") << FootfallCsv(WalkFootfalls(loop, walk));
  const StairplanRun found = RunStairplan(dir, "footfalls " + dir + "/walk.csv --nosing 0.02 --stairs-out " + dir + "/found.yaml");
  INFO(found.out << found.err);
  REQUIRE(found.code == 0);
  const char* found_files[4] = {"found.yaml", "found_1.yaml", "found_2.yaml", "found_3.yaml"};
  // Every flight's true stairs (the checks below read them all); planned and validated: all four,
  // under the sanitizers the first only.
  for (std::size_t i = 0; i < loop.size(); ++i) {
    std::ofstream(dir + "/true_" + std::to_string(i) + ".yaml") << StairSpecToYaml(loop[i].stairs.spec());
  }
  const std::size_t stride = FullOrSanitized<std::size_t>(1, loop.size());
  for (std::size_t i = 0; i < loop.size(); i += stride) {
    INFO("flight " << i);
    const std::string truth = dir + "/true_" + std::to_string(i) + ".yaml";
    // The footfalls' bound on their nosings, which the planners keep as clearance.
    const double uncertainty = StairSpecFromYamlFile(dir + "/" + found_files[i]).uncertainty;
    CHECK(uncertainty > 0.0);
    // The default (the body optimisation, which uses every millimetre it is given: without the
    // uncertainty its plans kept exactly its rows' clearance on the found stairs and 3.3-4.6 mm
    // on the true ones) and the quasi-static path baseline. Under the sanitizers the default only.
    std::vector<std::string> bodies = {std::string()};
    if (!kSanitized) bodies.push_back(std::string(kPathBaseline));
    for (const std::string& body : bodies) {
      INFO((body.empty() ? "default" : "path baseline"));
      const std::string out = dir + "/plan_" + std::to_string(i) + (body.empty() ? "" : "_path");
      const StairplanRun plan = RunStairplan(dir, "plan --stairs " + dir + "/" + found_files[i] + " " + body + " --out " + out);
      INFO(plan.out << plan.err);
      if (i == 0 && body.empty()) {
        // Not yet planned by the default: on the first flight (the 0.25 s cadence, 3 cm of
        // uncertainty, the 5 mm execution margin on top) the lateral crawl's hind legs are out of
        // reach as they lift (issue 18). The check turns red when the default plans it.
        CHECK(plan.code == 3);
        continue;
      }
      REQUIRE(plan.code == 0);
      const nlohmann::json clearance = nlohmann::json::parse(ReadFile(out + "/plan.json")).at("clearance");
      CHECK(clearance.at("stairs_uncertainty_m").get<double>() == uncertainty);
      CHECK(clearance.at("body_qp_margin_m").get<double>() == Approx(PipelineOptions{}.body_qp.clearance_margin + uncertainty));
      CHECK(clearance.at("validator_min_m").get<double>() == 0.005);
      const StairplanRun valid = RunStairplan(dir, "validate " + out + "/plan.json --stairs " + truth + " --json");
      INFO(valid.out << valid.err);
      CHECK(valid.code == 0);
    }
  }
  // plan --footfalls plans on a staircase of the log directly: the third, walked down. Not under the
  // sanitizers (a 7-step descent planned and replayed there took most of this test's 68 s); the
  // normal build runs it, and "the built-in robot's default descents validate" descends there.
  if (!kSanitized) {
    const StairplanRun direct =
        RunStairplan(dir, "plan --footfalls " + dir + "/walk.csv --staircase 3 --nosing 0.02 --out " + dir + "/direct");
    INFO(direct.out << direct.err);
    REQUIRE(direct.code == 0);
    CHECK(RunStairplan(dir, "validate " + dir + "/direct/plan.json --stairs " + dir + "/true_2.yaml").code == 0);
    {
      // Stair mode engaged where the log's track first came within range of that flight, and the
      // alignment pose is, in the world, the patent's pose for the true flight (seed 001
      // [0042]-[0043]) to within what the footfalls find of it.
      const nlohmann::json plan = nlohmann::json::parse(ReadFile(dir + "/direct/plan.json"));
      const nlohmann::json& mode = plan.at("stair_mode");
      CHECK(mode.at("engaged") == true);
      CHECK(mode.at("robot").at("source") == "footfall_track");
      CHECK(mode.at("distance_m").get<double>() <= 1.0);
      const StairModel truth = loop[2].Model();
      const nlohmann::json& robot_W = mode.at("robot").at("world");
      CHECK(DistanceToFlight(truth, {robot_W.at("x").get<double>(), robot_W.at("y").get<double>()}) < 1.05);
      const nlohmann::json& a = plan.at("alignment");
      const AlignmentPose exact = ComputeAlignmentPose(truth, TravelDirection::kDown, Facing::kForward, a.at("standoff_m").get<double>());
      const nlohmann::json& w = a.at("world");
      CHECK(std::hypot(w.at("x").get<double>() - exact.position.x(), w.at("y").get<double>() - exact.position.y()) < 0.05);
      CHECK(std::abs(std::remainder(w.at("yaw_rad").get<double>() - exact.yaw, 2.0 * M_PI)) < 2.0 * M_PI / 180.0);
    }
  }
  CHECK(RunStairplan(dir, "plan --footfalls " + dir + "/walk.csv --staircase 5 --out " + dir + "/none").code == 3);
  // The check has teeth: the first flight's plan (rise 0.17) on the second flight's stairs (0.15) is invalid.
  const StairplanRun wrong = RunStairplan(dir, "validate " + dir + "/plan_0/plan.json --stairs " + dir + "/true_1.yaml");
  INFO(wrong.out);
  CHECK(wrong.code == 3);
}
