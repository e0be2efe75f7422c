// `stairplan validate`: a written plan validates; a plan edited to put a foot off its tread is
// caught with exit 3; a broken plan.json exits 2 naming the field.
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "sanitized.h"
#include "test_paths.h"

using nlohmann::json;
using namespace stairplan::testing;

namespace {

int Validate(const std::string& args, const std::string& dir, std::string* out, std::string* err) {
  const int code = RunCommand(BinDir() + "/stairplan validate " + args, dir + "/v.out", dir + "/v.err");
  *out = ReadFile(dir + "/v.out");
  *err = ReadFile(dir + "/v.err");
  return code;
}

// `flags`: more `plan` flags (a shorter flight).
std::string WritePlan(const std::string& dir, const std::string& flags = "") {
  REQUIRE(RunCommand(BinDir() + "/stairplan plan --out " + dir + flags, dir + "/p.out", dir + "/p.err") == 0);
  return dir + "/plan.json";
}

}  // namespace

TEST_CASE("validate accepts the plan that plan wrote", "[cli][validate]") {
  const std::string dir = MakeTempDir("validate-ok");
  std::string out, err;
  // Under the sanitizers (a default plan and its validation took 18 s) a 3-step flight.
  CHECK(Validate(WritePlan(dir, FullOrSanitized<std::string>("", " --steps 3")) + " --json", dir, &out, &err) == 0);
  const json report = json::parse(out);
  CHECK(report["ok"] == true);
  CHECK(report["min_clearance_m"].get<double>() > 0.005);
}

TEST_CASE("validate catches a foot moved off its tread", "[cli][validate]") {
  const std::string dir = MakeTempDir("validate-fault");
  json plan = json::parse(ReadFile(WritePlan(dir)));
  json& step = plan["footsteps"][14];
  const int stair = step["stair_index"];
  const double x_end = plan["stairs"]["surfaces"][static_cast<std::size_t>(stair)]["x_end"];
  step["x"] = x_end - 0.005;  // against the riser above
  std::ofstream(dir + "/bad.json") << plan.dump();
  std::string out, err;
  CHECK(Validate(dir + "/bad.json", dir, &out, &err) == 3);
  CHECK_THAT(out, Catch::Contains("foot_outside_step_region"));
}

TEST_CASE("validate judges dynamics with validator settings and names a bad one", "[cli][validate]") {
  const std::string dir = MakeTempDir("validate-dynamics");
  const std::string plan = WritePlan(dir, FullOrSanitized<std::string>("", " --steps 3"));
  std::string out, err;
  // Reported by default: the summary line, the verdict untouched.
  CHECK(Validate(plan + " --set validator.friction=0.1", dir, &out, &err) == 0);
  CHECK_THAT(out, Catch::Contains("dynamics (report): FAILS"));
  // Judged: the slipping foot is a violation, exit 3, and the JSON names its family.
  CHECK(Validate(plan + " --set validator.friction=0.1 --set validator.dynamics=2 --json", dir, &out, &err) == 3);
  const json report = json::parse(out);
  CHECK(report["dynamics"]["mode"] == "judge");
  CHECK(report["dynamics"]["failed_instants"].get<int>() > 0);
  bool slip = false;
  for (const json& v : report["violations"]) slip = slip || (v["kind"] == "friction_cone" && v["family"] == "dynamics");
  CHECK(slip);
  CHECK(Validate(plan + " --set validator.frction=0.2", dir, &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("validator.frction"));
}

TEST_CASE("validate rejects broken plan files naming the field", "[cli][validate]") {
  const std::string dir = MakeTempDir("validate-bad");
  json plan = json::parse(ReadFile(WritePlan(dir, FullOrSanitized<std::string>("", " --steps 3"))));
  std::string out, err;
  const auto expect = [&](const json& doc, const std::string& named) {
    std::ofstream(dir + "/broken.json") << doc.dump();
    INFO(named << " -> " << err);
    CHECK(Validate(dir + "/broken.json", dir, &out, &err) == 2);
    CHECK_THAT(err, Catch::Contains("broken.json") && Catch::Contains(named));
  };
  json missing = plan;
  missing.erase("body");
  expect(missing, "body");
  json wrong = plan;
  wrong["footsteps"][3]["x"] = "far";
  expect(wrong, "footsteps[3].x");
  json bad_stairs = plan;
  bad_stairs["stairs"]["run"] = -0.2;
  expect(bad_stairs, "stairs.run");
  json bad_gait = plan;
  bad_gait["gait"] = "gallop";  // the validator's checks depend on the gait: no guessing
  expect(bad_gait, "gait");
  std::ofstream(dir + "/truncated.json") << plan.dump().substr(0, 200);
  CHECK(Validate(dir + "/truncated.json", dir, &out, &err) == 2);
  CHECK_THAT(err, Catch::Contains("truncated.json"));
  CHECK(Validate(dir + "/missing.json", dir, &out, &err) == 2);
}
