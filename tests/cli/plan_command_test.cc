// `stairplan plan` end to end: the files it writes, the geometry of every footstep checked
// against the stairs alone, and bad input that exits 2 naming the flag or field.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "stairplan/planning/plan.h"
#include "sanitized.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using nlohmann::json;
using stairplan::testing::BinDir;
using stairplan::testing::MakeTempDir;
using stairplan::testing::ReadFile;
using stairplan::testing::RunCommand;

namespace {

struct Run {
  int code = -1;
  std::string out;
  std::string err;
};

Run Plan(const std::string& args, const std::string& dir) {
  Run r;
  r.code = RunCommand(BinDir() + "/stairplan plan " + args, dir + "/stdout.txt", dir + "/stderr.txt");
  r.out = ReadFile(dir + "/stdout.txt");
  r.err = ReadFile(dir + "/stderr.txt");
  return r;
}

// `plan args` into dir/sub, which must exit 0, and the plan.json it wrote.
struct Planned {
  Run run;
  json plan;
};

Planned PlanInto(const std::string& args, const std::string& dir, const std::string& sub) {
  Planned p{Plan(args + " --out " + dir + "/" + sub, dir), json()};
  INFO(p.run.out << p.run.err);
  REQUIRE(p.run.code == 0);
  p.plan = json::parse(ReadFile(dir + "/" + sub + "/plan.json"));
  return p;
}

// Independent of the library: the default stairs rebuilt from the numbers in plan.json.
struct Tread {
  double x_begin, x_end, z;
};

std::vector<Tread> TreadsFromSpec(const json& stairs) {
  const int steps = stairs.at("steps");
  const double rise = stairs.at("rise"), run = stairs.at("run"), nosing = stairs.at("nosing");
  const bool up = stairs.at("direction") == "up";
  const double total = steps * rise;
  std::vector<Tread> treads;
  double begin = -stairs.at("landing_before").get<double>();
  for (int k = 0; k <= steps; ++k) {
    const double riser = k * run;  // riser k+1 stands at x = k * run (the first at 0)
    const double nose = up ? riser - nosing : riser + nosing;
    const double end = k < steps ? nose : (steps - 1) * run + stairs.at("landing_after").get<double>();
    treads.push_back({begin, end, up ? k * rise : total - k * rise});
    begin = nose;
  }
  return treads;
}

}  // namespace

TEST_CASE("plan writes plan.json and plan.svg with every footstep inside its step region", "[cli][plan]") {
  for (const std::string direction : {"up", "down"}) {
    for (const std::string facing : {"forward", "backward"}) {
      // Under the sanitizers the default climb and the backward descent: the other two take the
      // same code paths.
      if (stairplan::testing::kSanitized && (direction == "up") != (facing == "forward")) continue;
      const std::string dir = MakeTempDir("plan");
      // Under the sanitizers (planning ~20x slower) a 3-step flight, which still has every kind of tread.
      const std::string steps = stairplan::testing::FullOrSanitized<std::string>("", " --steps 3");
      const Run r = Plan("--out " + dir + "/out --direction " + direction + " --facing " + facing + steps, dir);
      INFO(direction << " " << facing << ": " << r.out << r.err);
      // The default (up, forward) must validate; the crawl baseline does not yet validate every
      // other direction and facing, and then exits 3 with the report in plan.json.
      const bool is_default = direction == "up" && facing == "forward";
      REQUIRE((r.code == 0 || (!is_default && r.code == 3)));
      CHECK_THAT(r.out, Catch::Contains("status:    ok"));
      REQUIRE(fs::exists(dir + "/out/plan.svg"));
      CHECK_THAT(ReadFile(dir + "/out/plan.svg"), Catch::StartsWith("<svg"));
      const json plan = json::parse(ReadFile(dir + "/out/plan.json"));
      for (const char* key : {"robot", "stairs", "footsteps", "body", "cadence_s", "status", "timing_us"}) {
        CHECK(plan.contains(key));
      }
      CHECK(plan["robot"]["name"] == "stairbot");
      CHECK(plan["robot"]["legs"].size() == 4);
      CHECK(plan["status"] == "ok");
      REQUIRE(plan.contains("validation"));
      CHECK(plan["validation"]["ok"] == (r.code == 0));
      if (is_default) {
        CHECK(plan["validation"]["violations"].empty());
        CHECK(plan["validation"]["min_clearance_m"].get<double>() > 0.005);
        CHECK(plan["validation"]["min_stability_margin_m"].get<double>() > 0.01);
      }
      CHECK(plan["cadence_s"].get<double>() > 0.0);
      const auto treads = TreadsFromSpec(plan["stairs"]);
      const double edge = 0.05, riser = 0.07, side = 0.10;  // the default margins
      const double half_width = plan["stairs"]["width"].get<double>() / 2;
      REQUIRE(plan["footsteps"].size() >= 4 * (treads.size() - 2));
      std::set<int> stairs_used;
      for (const auto& f : plan["footsteps"]) {
        const int k = f["stair_index"];
        REQUIRE(k >= 0);
        REQUIRE(k < static_cast<int>(treads.size()));
        const Tread& t = treads[static_cast<std::size_t>(k)];
        const double x = f["x"], y = f["y"], z = f["z"];
        CHECK(z == Approx(t.z).margin(1e-9));
        CHECK(x > t.x_begin);
        CHECK(x < t.x_end);
        CHECK(std::abs(y) <= half_width - side + 1e-9);
        const bool first = k == 0, last = k + 1 == static_cast<int>(treads.size());
        if (!first) CHECK(x - t.x_begin >= std::min(edge, riser) - 1e-9);
        if (!last) CHECK(t.x_end - x >= std::min(edge, riser) - 1e-9);
        CHECK(f["in_step_region"] == true);
        stairs_used.insert(k);
      }
      CHECK(stairs_used.size() == treads.size());  // every tread is stepped on
    }
  }
}

TEST_CASE("plan --json prints the same plan on stdout", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-json");
  const Run r = Plan("--json --steps 3 --out " + dir + "/out", dir);
  REQUIRE(r.code == 0);
  CHECK(json::parse(r.out)["validation"]["ok"] == true);
  const json printed = json::parse(r.out);
  const json written = json::parse(ReadFile(dir + "/out/plan.json"));
  CHECK(printed["footsteps"] == written["footsteps"]);
  CHECK(printed["stairs"]["steps"] == 3);
  // No robot pose given: it is taken to stand at the alignment pose, in stair mode.
  CHECK(written["stair_mode"]["engaged"] == true);
  CHECK(written["stair_mode"]["robot"]["source"] == "alignment");
  // Without --align-start the feet start on the crawl's footholds: a few centimetres off the pose.
  CHECK(written["alignment"]["plan_start_offset_m"].get<double>() > 0.0);
}

TEST_CASE("plan --start: out of stair mode's range it warns, and the plan still starts at the alignment pose", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-start");
  const Run r = Plan("--steps 3 --align-start --start=-2.5,0.4,1.5 --out " + dir + "/out", dir);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("stair mode is not engaged"));
  const json plan = json::parse(ReadFile(dir + "/out/plan.json"));
  const json& mode = plan["stair_mode"];
  CHECK(mode["engaged"] == false);
  CHECK(mode["robot"]["source"] == "given");
  CHECK(mode["robot"]["x"] == -2.5);
  CHECK(mode["distance_m"].get<double>() == Approx(2.5 - plan["stairs"]["nosing"].get<double>()));
  CHECK(mode["engage_distance_m"] == 1.0);
  const json& a = plan["alignment"];
  CHECK(a["found"] == true);
  CHECK(a["y"] == 0.0);
  CHECK(a["yaw_rad"] == 0.0);
  CHECK(a["turn_rad"].get<double>() == Approx(-1.5));
  CHECK(a["plan_start_offset_m"].get<double>() < 0.002);
  CHECK(plan["body"][0]["x"].get<double>() == Approx(a["x"].get<double>()).margin(0.002));
  CHECK(a["feet"].size() == 4);
  // Closer than --engage-distance: in stair mode, no warning.
  const Run near = Plan("--steps 3 --start=-2.5,0.4,1.5 --engage-distance 3 --out " + dir + "/near", dir);
  REQUIRE(near.code == 0);
  CHECK(near.err.empty());
  CHECK(json::parse(ReadFile(dir + "/near/plan.json"))["stair_mode"]["engaged"] == true);
}

TEST_CASE("plan.json names the body planner and, for the receding horizon, carries every cycle's solve", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-cycles");
  const json by_path = PlanInto("--steps 2 --body path", dir, "path").plan;
  CHECK(by_path["body_planner"] == "quasi_static_path");
  CHECK(by_path["body_cycles"]["count"] == 0);

  // The default horizon (1 s) under the sanitizers too: since knot 1 keeps the acceleration limits
  // with the body executed a cycle ago, a horizon shorter than about 0.9 s sees the second step too
  // late to climb it within them (30 knots 25 ms apart: joint limits at t = 7.2 s).
  const Run qp = Plan("--steps 2 --out " + dir + "/qp", dir);  // the default
  INFO(qp.out << qp.err);
  REQUIRE(qp.code == 0);  // with its support and leg rows the body optimisation's plan validates
  const json plan = json::parse(ReadFile(dir + "/qp/plan.json"));
  CHECK(plan["body_planner"] == "receding_horizon_qp");
  const json& cycles = plan["body_cycles"];
  // One cycle per body sample, as a control loop would have run it.
  REQUIRE(cycles["count"] == plan["body"].size());
  const json& per = cycles["per_cycle"];
  for (const char* key : {"t", "status", "solves", "iterations", "solve_us", "total_us", "relaxation"}) {
    INFO(key);
    CHECK(per[key].size() == plan["body"].size());
  }
  // The executed knot's relaxation is a share of violations; `relaxed` counts the cycles with any.
  int relaxed = 0;
  for (const json& r : per["relaxation"]) {
    CHECK(r.get<double>() >= 0.0);
    CHECK(r.get<double>() <= 1.0);
    stairplan::BodyCycleStats cycle;
    cycle.relaxation = r.get<double>();
    relaxed += cycle.relaxed() ? 1 : 0;
  }
  CHECK(cycles["relaxed"] == relaxed);
  for (std::size_t i = 0; i < plan["body"].size(); ++i) CHECK(per["t"][i] == plan["body"][i]["t"]);
  // The first cycle converges the linearisation (several QPs); nearly all later ones solve one warm QP.
  CHECK(per["solves"][0].get<int>() > 1);
  std::size_t single = 0;
  for (std::size_t i = 1; i < per["solves"].size(); ++i) single += per["solves"][i] == 1 ? 1 : 0;
  CHECK(single >= 9 * (per["solves"].size() - 1) / 10);
  CHECK(cycles["stale"] == 0);
  CHECK(cycles["solve_us_p99"].get<double>() >= cycles["solve_us_p50"].get<double>());
  CHECK(cycles["iterations_max"].get<int>() >= 1);
  // validate reads the plan back.
  const int code = RunCommand(BinDir() + "/stairplan validate " + dir + "/qp/plan.json", dir + "/v.txt", dir + "/v.err");
  INFO(ReadFile(dir + "/v.txt") << ReadFile(dir + "/v.err"));
  CHECK(code == 0);
}

TEST_CASE("plan --gait auto trots down the default stairs and walks up them, saying why not the trot", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-gait");
  const Planned down = PlanInto("--gait auto --direction down", dir, "down");
  CHECK(down.plan["gait"] == "trot");
  CHECK(down.plan["rejected_gaits"].empty());
  CHECK(down.plan["validation"]["dynamics"]["mode"] == "judge");
  CHECK_THAT(down.run.out, Catch::Contains("gait:      trot"));
  const Planned up = PlanInto("--gait auto", dir, "up");
  const json& walk = up.plan;
  CHECK(walk["gait"] == "walk");
  REQUIRE(walk["rejected_gaits"].size() == 1);
  CHECK(walk["rejected_gaits"][0]["gait"] == "trot");
  const std::string reason = walk["rejected_gaits"][0]["reason"];
  CHECK_THAT(reason, Catch::Contains("wrench_unattainable") || Catch::Contains("torque_limit") ||
                         Catch::Contains("friction_cone") || Catch::Contains("support_line_tilt"));
  CHECK_THAT(up.run.out, Catch::Contains("not the trot: " + reason));
}

TEST_CASE("plan --gait trot reports its flight and speed, in the summary and plan.json", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-trot");
  const Run run = Plan("--gait trot --out " + dir + "/trot", dir);
  INFO(run.out << run.err);
  // Planned, and rejected by the dynamic check (README: the trot's verdict): exit 3.
  REQUIRE(run.code == 3);
  const Planned trot{run, json::parse(ReadFile(dir + "/trot/plan.json"))};
  CHECK(trot.plan["gait"] == "trot");
  CHECK(trot.plan["status"] == "ok");
  // 18 pair swings of 0.25 s, 0.15 s apart: the first liftoff at 0.15 s, the last touchdown at 7.2 s.
  CHECK(trot.plan["flight_s"].get<double>() == Approx(18 * 0.4 - 0.15).margin(1e-9));
  const double speed = trot.plan["speed_m_s"];
  CHECK(speed > 0.3);
  CHECK(speed < 0.4);
  CHECK_THAT(trot.run.out, Catch::Contains("flight 7.05 s from the first liftoff to the last touchdown"));
  CHECK_THAT(trot.run.out, Catch::Contains(" m/s"));
}

TEST_CASE("plan rejects bad input with exit 2, names it, and writes nothing", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-bad");
  const auto expect_bad = [&](const std::string& args, const std::string& named) {
    const Run r = Plan(args + " --out " + dir + "/out", dir);
    INFO(args << " -> " << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(named));
    CHECK_FALSE(fs::exists(dir + "/out/plan.json"));
  };
  expect_bad("--rise -1", "--rise");
  expect_bad("--rise abc", "--rise");
  expect_bad("--run 0", "--run");
  expect_bad("--steps 0", "--steps");
  expect_bad("--nosing 0.2", "--nosing");
  expect_bad("--direction sideways", "--direction");
  expect_bad("--facing left", "--facing");
  expect_bad("--crawl-sequence trot", "--crawl-sequence");
  expect_bad("--gait gallop", "--gait");
  expect_bad("--gait walk --planner step", "--gait");
  expect_bad("--robot /nonexistent.urdf", "/nonexistent.urdf");
  expect_bad("--stairs /nonexistent.yaml", "/nonexistent.yaml");
  expect_bad("--no-such-flag", "--no-such-flag");
  expect_bad("--set body.no_such_setting=1", "no_such_setting");
  expect_bad("--set body.stability_margin=abc", "abc");
  expect_bad("--set body.knots=2", "knots");
  expect_bad("--set stability_margin=0.03", "body.NAME=VALUE");
  expect_bad("--planner paper --cloud " + dir + "/any.ply", "--cloud");  // the paper's crawl needs known stairs
  expect_bad("--start 1,2", "--start");
  expect_bad("--start 1,nan,0", "--start");
  expect_bad("--engage-distance -1", "--engage-distance");
  {
    std::ofstream(dir + "/negative.yaml") << "steps: 5\nrun: -0.27\n";
    expect_bad("--stairs " + dir + "/negative.yaml", "'run'");
  }
  {
    std::ofstream(dir + "/broken.urdf") << "<robot name='x'><link name='a'/><joint name='j' type='fixed'>";
    expect_bad("--robot " + dir + "/broken.urdf", "broken.urdf");
  }
}

TEST_CASE("plan with a stairs YAML and flag overrides", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-yaml");
  std::ofstream(dir + "/stairs.yaml") << "steps: 4\nrise: 0.15\nrun: 0.30\ndirection: down\n";
  const Run r = Plan("--stairs " + dir + "/stairs.yaml --rise 0.16 --out " + dir + "/out", dir);
  REQUIRE((r.code == 0 || r.code == 3));  // 3: planned, but the crawl baseline fails validation going down
  const json plan = json::parse(ReadFile(dir + "/out/plan.json"));
  CHECK(plan["stairs"]["steps"] == 4);
  CHECK(plan["stairs"]["rise"].get<double>() == Approx(0.16));
  CHECK(plan["stairs"]["run"].get<double>() == Approx(0.30));
  CHECK(plan["stairs"]["direction"] == "down");
}

TEST_CASE("plan reports infeasible stairs with exit 3 and still writes the JSON", "[cli][plan]") {
  const std::string dir = MakeTempDir("plan-infeasible");
  std::ofstream(dir + "/short.yaml") << "landing_after: 0.2\n";
  const Run r = Plan("--stairs " + dir + "/short.yaml --out " + dir + "/out", dir);
  CHECK(r.code == 3);
  const json plan = json::parse(ReadFile(dir + "/out/plan.json"));
  CHECK(plan["status"] == "infeasible");
  CHECK_THAT(plan["status_reason"].get<std::string>(), Catch::Contains("landing_after"));
}
