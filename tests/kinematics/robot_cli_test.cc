// `stairplan plan --robot FILE`: works for every real robot, and bad URDFs exit 2 naming the file
// and the element.
#include <catch2/catch.hpp>

#include <fstream>

#include "stairplan/kinematics/builtin_robot.h"
#include "robot_files.h"
#include "sanitized.h"

using stairplan::testing::BinDir;
using stairplan::testing::MakeTempDir;
using stairplan::testing::ReadFile;
using stairplan::testing::RunCommand;

namespace {

struct Run {
  int code = -1;
  std::string err;
};

Run Plan(const std::string& robot_path, const std::string& dir) {
  Run run;
  const std::string robot = robot_path.empty() ? "" : " --robot '" + robot_path + "'";
  // A 2-step flight: loading the robot is what is tested (every shared robot's whole flight through
  // the CLI's pipeline is planned and checked in tests/collision/plan_stance_test.cc).
  run.code = RunCommand(BinDir() + "/stairplan plan" + robot + " --steps 2 --out '" + dir + "/out'", dir + "/stdout", dir + "/stderr");
  run.err = ReadFile(dir + "/stderr");
  return run;
}

std::string WriteUrdf(const std::string& dir, const std::string& name, std::string text, const std::string& from,
                      const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("stairplan plan --robot works for every robot", "[robot_cli]") {
  const std::string dir = MakeTempDir("robot-cli");
  for (const auto& file : stairplan::testing::TestRobots()) {
    // Under the sanitizers, where a plan takes up to a minute, the built-in robot and one shared
    // URDF (the loader's own tests read every shared robot there): ANYmal C's 2-step plan takes
    // 10 s there, Go2's a minute (its retries and foothold search).
    if (stairplan::testing::kSanitized && file.label != "stairbot" && file.label != "anymal_c") continue;
    INFO(file.label);
    const Run run = Plan(file.path, dir);
    // The robot loads and a plan is written; whether the plan validates (0) or not (3) is the
    // planner's business (see tests/collision/plan_stance_test.cc), a bad robot would be 2.
    CHECK((run.code == 0 || run.code == 3));
    CHECK(run.err.empty());
    CHECK(ReadFile(dir + "/out/plan.json").find("\"footsteps\"") != std::string::npos);
  }
}

TEST_CASE("bad URDFs exit 2 naming the file and the element", "[robot_cli]") {
  const std::string dir = MakeTempDir("robot-cli-bad");
  const std::string& urdf = stairplan::BuiltinRobotUrdf();
  struct Case {
    std::string name, from, to, element;
  };
  const std::vector<Case> cases = {
      {"malformed.urdf", "</link>", "</lnk>", "</lnk>"},
      {"missing_link.urdf", "<child link=\"LH_thigh\"/>", "<child link=\"LH_thighs\"/>", "<joint name=\"LH_HFE\">"},
      {"capsule.urdf", "<cylinder radius=\"0.018\" length=\"0.22\"/>", "<capsule radius=\"0.018\" length=\"0.22\"/>",
       "<link name=\"LF_shank\">"},
      // A joint whose parent is its own child: urdfdom accepts it, and walking up the leg never ended.
      {"loop.urdf", "<parent link=\"LF_thigh\"/>", "<parent link=\"LF_shank\"/>", "<joint name=\"LF_KFE\">"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string path = WriteUrdf(dir, c.name, urdf, c.from, c.to);
    const Run run = Plan(path, dir);
    CHECK(run.code == 2);
    CHECK_THAT(run.err, Catch::Contains(path));
    CHECK_THAT(run.err, Catch::Contains(c.element));
  }
  // No feet: one leg cut off leaves three.
  const std::string cut = urdf.substr(0, urdf.find("<joint name=\"RH_HAA\"")) + "</robot>\n";
  const std::string path = dir + "/three_legs.urdf";
  std::ofstream(path) << cut;
  const Run run = Plan(path, dir);
  CHECK(run.code == 2);
  CHECK_THAT(run.err, Catch::Contains(path));
  CHECK_THAT(run.err, Catch::Contains("<link>: expected 4 feet"));
}
