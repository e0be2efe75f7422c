// Versions (issue #25): `stairplan --version`, and the version and schema_version that every JSON
// object the commands print or write carries, from the one generated "stairplan/version.h".
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "stairplan/version.h"
#include "test_paths.h"

using namespace stairplan::testing;

namespace {

void CheckVersioned(const nlohmann::json& j) {
  REQUIRE(j.is_object());
  CHECK(j.value("version", "") == std::string(stairplan::kVersion));
  CHECK(j.value("schema_version", -1) == stairplan::kSchemaVersion);
}

const char* kSmallQps =
    "NAME          T\nROWS\n N  obj\n G  c1\nCOLUMNS\n    x1  obj  1.0  c1  1.0\n    x2  obj  1.0  c1  1.0\n"
    "RHS\n    rhs  c1  1.0\nQUADOBJ\n    x1  x1  2.0\n    x2  x2  2.0\nENDATA\n";

}  // namespace

TEST_CASE("stairplan --version and -V print the version", "[cli][version]") {
  const std::string dir = MakeTempDir("version");
  for (const char* flag : {"--version", "-V"}) {
    const StairplanRun o = RunStairplan(dir, flag);
    CHECK(o.code == 0);
    CHECK(o.out == "stairplan " + std::string(stairplan::kVersion) + " (file schema " + std::to_string(stairplan::kSchemaVersion) + ")\n");
  }
  CHECK_THAT(std::string(stairplan::kVersion), Catch::Matches("[0-9]+\\.[0-9]+\\.[0-9]+"));
  CHECK_THAT(RunStairplan(dir, "--help").out, Catch::Contains("stairplan --version"));
}

// map and footfalls are checked in tests/perception/cloud_formats_cli_test.cc, simulate below.
TEST_CASE("plan.json and every command's JSON carry version and schema_version", "[cli][version]") {
  const std::string dir = MakeTempDir("version-json");
  const StairplanRun plan = RunStairplan(dir, "plan --steps 1 --out " + dir + "/plan");
  INFO(plan.err);
  REQUIRE((plan.code == 0 || plan.code == 3));
  const std::string plan_json = dir + "/plan/plan.json";
  CheckVersioned(nlohmann::json::parse(ReadFile(plan_json)));
  std::ofstream(dir + "/t.qps") << kSmallQps;
  const std::string commands[] = {
      "validate --json " + plan_json,
      "gait-design --json --rise 0.17 --run 0.27 --lmax 0.21 --body-length 0.444",
      "qp solve --json " + dir + "/t.qps",
  };
  for (const std::string& args : commands) {
    const StairplanRun o = RunStairplan(dir, args);
    INFO(args << "\n" << o.err);
    CHECK((o.code == 0 || o.code == 3));
    CheckVersioned(nlohmann::json::parse(o.out));
  }
}

TEST_CASE("simulate prints a summary by default, like every command, and its JSON with --json", "[cli][version]") {
  const std::string dir = MakeTempDir("simulate-summary");
  const std::string plan = SourceDir() + "/tests/fuzz/corpus/plan_json/minimal.json";
  const StairplanRun summary = RunStairplan(dir, "simulate " + plan + " --out " + dir + "/sim.json");
  INFO(summary.err);
  CHECK((summary.code == 0 || summary.code == 3));
  CHECK_THAT(summary.out, Catch::StartsWith("stairplan simulate: " + plan));
  CHECK(summary.out.find('{') == std::string::npos);
  // --out still holds the JSON, which --json prints.
  const nlohmann::json written = nlohmann::json::parse(ReadFile(dir + "/sim.json"));
  CheckVersioned(written);
  const StairplanRun printed = RunStairplan(dir, "simulate --json " + plan);
  CHECK(printed.code == summary.code);
  CHECK(nlohmann::json::parse(printed.out)["status"] == written["status"]);
}

TEST_CASE("simulate --stance-forces: the crawl's wrench by default, the convex MPC on request, a bad source exit 2",
          "[cli][simulation]") {
  const std::string dir = MakeTempDir("simulate-stance-forces");
  const std::string plan = SourceDir() + "/tests/fuzz/corpus/plan_json/minimal.json";
  const StairplanRun by_gait = RunStairplan(dir, "simulate --json " + plan);
  INFO(by_gait.err);
  REQUIRE((by_gait.code == 0 || by_gait.code == 3));
  CHECK(nlohmann::json::parse(by_gait.out)["stance_forces"] == "wrench");
  const StairplanRun mpc = RunStairplan(dir, "simulate --json --stance-forces mpc " + plan);
  REQUIRE((mpc.code == 0 || mpc.code == 3));
  CHECK(nlohmann::json::parse(mpc.out)["stance_forces"] == "mpc");
  const StairplanRun bad = RunStairplan(dir, "simulate --stance-forces magic " + plan);
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains("--stance-forces"));
}
