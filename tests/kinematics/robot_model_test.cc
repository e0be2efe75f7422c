// RobotModel on real robots: four legs found and named by where their hips are; bad URDFs are
// refused with a message naming the source and the element.
#include <catch2/catch.hpp>

#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_model.h"
#include "robot_files.h"

using stairplan::BuiltinRobot;
using stairplan::BuiltinRobotUrdf;
using stairplan::RobotModel;
using stairplan::testing::TestRobots;

namespace {

RobotModel Load(const stairplan::testing::RobotFile& file) {
  return file.path.empty() ? BuiltinRobot() : RobotModel::FromUrdfFile(file.path);
}

// The exception text of loading `xml`, or "" when it loads.
std::string LoadError(const std::string& xml, const stairplan::LegDetectionSettings& settings = {}) {
  try {
    RobotModel::FromUrdfString(xml, "bad.urdf", settings);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("every robot has four legs named by hip position, with the right feet", "[robot_model]") {
  const auto robots = TestRobots();
  if (robots.size() == 1) WARN("shared robots skipped: ../shared not found");
  for (const auto& file : robots) {
    INFO(file.label);
    const RobotModel robot = Load(file);
    REQUIRE(robot.legs().size() == 4);
    CHECK(robot.legs()[0].name == "LF");
    CHECK(robot.legs()[1].name == "RF");
    CHECK(robot.legs()[2].name == "LH");
    CHECK(robot.legs()[3].name == "RH");
    CHECK(robot.leg("LF").foot_link == file.foot_lf);
    CHECK(robot.leg("RF").foot_link == file.foot_rf);
    CHECK(robot.leg("LH").foot_link == file.foot_lh);
    CHECK(robot.leg("RH").foot_link == file.foot_rh);
    for (const auto& leg : robot.legs()) {
      INFO(leg.name);
      CHECK(leg.joint_names.size() == 3);
      CHECK(leg.foot_radius > 0.0);
      CHECK((leg.hip_B.x() > 0.0) == (leg.name[1] == 'F'));
      CHECK((leg.hip_B.y() > 0.0) == (leg.name[0] == 'L'));
    }
    CHECK(robot.hip_length() > 0.3);
    CHECK(robot.hip_width() > 0.05);
  }
}

TEST_CASE("the README's hip spans and foot sphere offsets are read", "[robot_model]") {
  const std::string a1 = stairplan::testing::SharedPath("data/robots/unitree_a1.urdf");
  if (a1.empty()) {
    WARN("shared robots skipped: ../shared not found");
    return;
  }
  const RobotModel robot = RobotModel::FromUrdfFile(a1);
  CHECK(robot.base_link() == "trunk");  // the inertia-less root `base` hangs the trunk on a fixed joint
  CHECK(robot.hip_length() == Approx(0.361));
  CHECK(robot.hip_width() == Approx(0.094));
  const RobotModel anymal = RobotModel::FromUrdfFile(stairplan::testing::SharedPath("data/robots/anymal_c.urdf"));
  CHECK(anymal.leg("LH").foot_sphere_center.z() == Approx(0.0225));
  CHECK(anymal.leg("LH").foot_radius == Approx(0.03));
}

TEST_CASE("settable foot names override the automatic rule", "[robot_model]") {
  stairplan::LegDetectionSettings settings;
  settings.foot_links = {"LF_shank", "RF_shank", "LH_shank", "RH_shank"};
  const RobotModel robot = RobotModel::FromUrdfString(BuiltinRobotUrdf(), "stairbot", settings);
  CHECK(robot.leg("LF").foot_link == "LF_shank");
  CHECK(robot.leg("LF").foot_radius == 0.0);
  settings.foot_links = {"LF_shank", "RF_shank", "LH_shank", "nope"};
  CHECK_THAT(LoadError(BuiltinRobotUrdf(), settings), Catch::Contains("nope"));
}

TEST_CASE("malformed XML names the file and the line", "[robot_model]") {
  const std::string xml = Replace(BuiltinRobotUrdf(), "</link>", "</lnk>");
  const std::string error = LoadError(xml);
  CHECK_THAT(error, Catch::StartsWith("bad.urdf"));
  CHECK_THAT(error, Catch::Contains("malformed XML"));
  CHECK_THAT(error, Catch::Contains("line"));
}

TEST_CASE("a joint naming a missing link names the joint and the link", "[robot_model]") {
  const std::string xml = Replace(BuiltinRobotUrdf(), "<child link=\"LH_thigh\"/>", "<child link=\"LH_thighs\"/>");
  const std::string error = LoadError(xml);
  CHECK_THAT(error, Catch::StartsWith("bad.urdf"));
  CHECK_THAT(error, Catch::Contains("LH_thighs"));
  CHECK_THAT(error, Catch::Contains("LH_HFE"));
}

TEST_CASE("a robot without four feet is refused naming what was found", "[robot_model]") {
  std::string xml = BuiltinRobotUrdf();
  // Cut the hind-right leg off: its hip joint now hangs from nothing movable.
  const auto begin = xml.find("<joint name=\"RH_HAA\"");
  const auto end = xml.find("</robot>");
  xml = xml.substr(0, begin) + xml.substr(end);
  const std::string error = LoadError(xml);
  CHECK_THAT(error, Catch::StartsWith("bad.urdf"));
  CHECK_THAT(error, Catch::Contains("expected 4 feet"));
  CHECK_THAT(error, Catch::Contains("found 3"));
}

TEST_CASE("a link whose only collision is a capsule is named", "[robot_model]") {
  const std::string xml = Replace(BuiltinRobotUrdf(), "<cylinder radius=\"0.018\" length=\"0.22\"/>",
                                  "<capsule radius=\"0.018\" length=\"0.22\"/>");
  const std::string error = LoadError(xml);
  CHECK_THAT(error, Catch::StartsWith("bad.urdf"));
  CHECK_THAT(error, Catch::Contains("LF_shank"));
  CHECK_THAT(error, Catch::Contains("capsule"));
}

TEST_CASE("an empty or missing file is refused", "[robot_model]") {
  CHECK_THAT(LoadError("  \n"), Catch::Contains("empty"));
  CHECK_THROWS_WITH(RobotModel::FromUrdfFile("/nonexistent/robot.urdf"), Catch::Contains("/nonexistent/robot.urdf"));
}
