// The viewer's C++ side: the robot's shapes posed through the validator's IK for every shared
// robot, the scene's frames and violation places, bad simulation output named by file and field,
// and a page whose data cannot end its own script element.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/viewer/viewer_page.h"
#include "stairplan/viewer/viewer_robot.h"
#include "stairplan/viewer/viewer_scene.h"
#include "test_paths.h"

namespace {

using nlohmann::json;
using stairplan::BodyPose;
using stairplan::LegAngles;
using stairplan::RobotModel;
using stairplan::ViewerRobot;
using stairplan::ViewerShape;
using stairplan::ViewerShapeType;

std::vector<RobotModel> ViewerTestRobots() {
  std::vector<RobotModel> robots{stairplan::BuiltinRobot()};
  const std::string dir = stairplan::testing::SharedPath("data/robots");
  if (dir.empty()) {
    WARN("../shared is absent: only the built-in robot is drawn");
    return robots;
  }
  for (const char* name : {"unitree_a1", "unitree_go1", "unitree_go2", "anymal_b", "anymal_c"}) {
    robots.push_back(RobotModel::FromUrdfFile(dir + "/" + name + ".urdf"));
  }
  return robots;
}

stairplan::PlanFile ViewerShortPlan(json* text) {
  const std::string path = stairplan::testing::SourceDir() + "/tests/fuzz/corpus/plan_json/short_plan.json";
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  *text = json::parse(buffer.str());
  return stairplan::ReadPlanJson(buffer.str(), path);
}

}  // namespace

TEST_CASE("viewer robot: each foot's shape rests on the contact point the IK was given, for every robot", "[viewer]") {
  const stairplan::Staircase stairs{stairplan::StairSpec{}};
  for (const RobotModel& robot : ViewerTestRobots()) {
    INFO(robot.name());
    ViewerRobot viewer(robot, stairs);
    REQUIRE(!viewer.shapes().empty());
    // A stance the legs can take: each foot where its nominal posture puts it.
    BodyPose body;
    body.position_W = {0.3, 0.05, 0.6};
    body.pitch = -0.1;
    std::array<Eigen::Vector3d, 4> contacts;
    for (int l = 0; l < 4; ++l) {
      const auto& leg = viewer.kinematics().leg(l);
      stairplan::LegWorkspace ws(leg);
      const Eigen::Isometry3d foot_W = body.ToIsometry() * leg.FootPose(leg.nominal(), ws);
      contacts[static_cast<std::size_t>(l)] =
          foot_W * leg.model().foot_sphere_center - leg.model().foot_radius * Eigen::Vector3d::UnitZ();
    }
    const LegAngles q = viewer.PlanAngles(body, contacts);
    std::vector<Eigen::Isometry3d> poses;
    viewer.ShapePoses(body, q, &poses);
    REQUIRE(poses.size() == viewer.shapes().size());
    int feet = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const ViewerShape& s = viewer.shapes()[i];
      CHECK(poses[i].matrix().allFinite());
      CHECK((poses[i].linear() * poses[i].linear().transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9);
      if (s.leg < 0 || s.type != ViewerShapeType::kSphere) continue;
      const auto& leg = viewer.kinematics().leg(s.leg).model();
      if (s.link != leg.foot_link) continue;
      ++feet;
      const Eigen::Vector3d expected = contacts[static_cast<std::size_t>(s.leg)] + leg.foot_radius * Eigen::Vector3d::UnitZ();
      CHECK((poses[i].translation() - expected).norm() < 1e-3);
    }
    CHECK(feet == 4);
  }
}

TEST_CASE("viewer scene: a pose per shape and frame, violations at their footstep, bad input named", "[viewer]") {
  json plan_json;
  const stairplan::PlanFile file = ViewerShortPlan(&plan_json);
  const RobotModel& robot = stairplan::BuiltinRobot();
  const stairplan::Footstep& step = file.plan.footsteps.front();
  const json report = {{"ok", false},
                       {"violations", {{{"t", step.t_touchdown}, {"leg", step.leg}, {"kind", "foot_outside_step_region"},
                                        {"value", 0.04}, {"detail", "stair 0"}},
                                       {{"t", file.plan.body[2].t}, {"leg", "body"}, {"kind", "stability"}, {"value", -0.01}}}}};
  stairplan::ViewerSceneSettings settings;
  settings.frame_period = 0.05;
  const json scene = stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"},
                                                 {&report, "report.json"}, {nullptr, ""}, settings);
  const std::size_t frames = static_cast<std::size_t>(std::ceil(file.plan.duration() / 0.05 - 1e-9)) + 1;
  CHECK(scene["frames"]["t"].size() == frames);
  CHECK(scene["frames"]["poses"].size() == frames * scene["robot"]["shapes"].size() * 7);
  CHECK_FALSE(scene["valid"].get<bool>());
  CHECK(scene["title"].get<std::string>().find("INVALID: foot_outside_step_region") != std::string::npos);
  REQUIRE(scene["violations"].size() == 2);
  const json& p = scene["violations"][0]["p"];
  CHECK(std::abs(p[0].get<double>() - step.position_W.x()) < 1e-3);
  CHECK(std::abs(p[1].get<double>() - step.position_W.y()) < 1e-3);
  const json& body = scene["violations"][1]["p"];  // the body's, at its sample
  CHECK(std::abs(body[0].get<double>() - file.plan.body[2].x) < 1e-3);
  CHECK(std::abs(body[2].get<double>() - file.plan.body[2].z) < 1e-3);
  CHECK(scene["regions"].size() == plan_json["map"]["stairs"].size());

  // A simulated run: one frame, and one with a base of two numbers.
  const json leg_q = {0.0, 0.5, -1.0};
  json sim = {{"status", "success"},
              {"frames", {{{"t", 0.0}, {"base", {0.0, 0.0, 0.5}}, {"roll_pitch_yaw", {0.0, 0.0, 0.0}},
                           {"q", {{"LF", leg_q}, {"RF", leg_q}, {"LH", leg_q}, {"RH", leg_q}}}}}}};
  const json with_sim = stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"}, {nullptr, ""},
                                                    {&sim, "sim.json"}, settings);
  CHECK(with_sim["sim"]["poses"].size() == scene["robot"]["shapes"].size() * 7);
  // Its impacts: each drawn where it happened and listed with its response; one without its place is refused.
  sim["impacts"] = {{{"t", 0.5}, {"leg", "LF"}, {"kind", "contralateral_strike"}, {"response", "adjust_step"},
                     {"executed", true}, {"reason", "shifted away"}, {"at", {0.1, 0.0, 0.2}}, {"target", {0.1, 0.06, 0.17}}},
                    {{"t", 0.6}, {"leg", "LF"}, {"kind", "touchdown"}, {"response", "classify_stance"},
                     {"executed", true}, {"reason", "touchdown on time"}, {"at", {0.1, 0.06, 0.17}}, {"target", {0.1, 0.06, 0.17}}}};
  const json with_impacts = stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"}, {nullptr, ""},
                                                        {&sim, "sim.json"}, settings);
  REQUIRE(with_impacts["sim"]["impacts"].size() == 2);
  CHECK(with_impacts["sim"]["impacts"][0]["target"][1].get<double>() == Approx(0.06));
  CHECK(with_impacts["sim"]["impacts"][1]["p"][2].get<double>() == Approx(0.17));
  const std::string page = stairplan::ViewerPageHtml(with_impacts, "");
  CHECK(page.find("Impacts (1, and 1 touchdowns)") != std::string::npos);
  CHECK(page.find("LF contralateral_strike -&gt; adjust_step") != std::string::npos);
  sim["impacts"][1].erase("at");
  CHECK_THROWS_WITH(stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"}, {nullptr, ""},
                                                {&sim, "sim.json"}, settings),
                    Catch::Contains("sim.json: field 'impacts[1].at'"));
  sim.erase("impacts");
  sim["frames"][0]["base"] = {0.0, 0.0};
  CHECK_THROWS_WITH(stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"}, {nullptr, ""},
                                                {&sim, "sim.json"}, settings),
                    Catch::Contains("sim.json: field 'frames[0].base'"));
  json bad_report = report;
  bad_report["violations"][0].erase("t");
  CHECK_THROWS_WITH(stairplan::BuildViewerScene(robot, file, {&plan_json, "short_plan.json"},
                                                {&bad_report, "report.json"}, {nullptr, ""}, settings),
                    Catch::Contains("report.json: field 'violations[0].t'"));
}

TEST_CASE("viewer page: text in the scene cannot end its script element", "[viewer]") {
  const json scene = {{"title", "x </script><script>alert(1)</script>"}, {"valid", false},
                      {"violations", json::array()}, {"sim", nullptr}};
  const std::string html = stairplan::ViewerPageHtml(scene, "/* script */");
  std::size_t closes = 0;
  for (std::size_t at = html.find("</script>"); at != std::string::npos; at = html.find("</script>", at + 1)) ++closes;
  CHECK(closes == 2);  // the data's and the script's own
  CHECK(html.find("</script>") == html.find("</script>\n<script>/* script */"));
  CHECK(html.find("<h1 class=\"invalid\">x &lt;/script&gt;") != std::string::npos);
}
