// `stairplan view plan.json --html OUT.html`: one self-contained page (three.js inline) showing the
// plan in 3D: stairs, map regions, footsteps, the body path, the robot posed by the plan's joint
// angles, its violations, and with --sim the MuJoCo run as a second, translucent robot.
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/cli_common.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/viewer/viewer_bundle.h"
#include "stairplan/viewer/viewer_page.h"
#include "stairplan/viewer/viewer_scene.h"

namespace stairplan::cli {
namespace {

std::string ReadText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path + ": cannot open the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json ParseJson(const std::string& text, const std::string& path) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(path + ": not valid JSON (" + e.what() + ")");
  }
}

int RunView(const std::vector<std::string>& args) {
  CLI::App app("Write a self-contained 3D viewer page (HTML, three.js inline) of a plan and its simulation", "view");
  std::string path, robot_path, sim_path, validation_path, html;
  ViewerSceneSettings settings;
  app.add_option("plan", path, "plan.json written by `stairplan plan`")->required();
  app.add_option("--robot", robot_path, "Robot URDF (default: the one the plan names)");
  app.add_option("--sim", sim_path, "Output of `stairplan simulate --out SIM.json --frame-ms MS`: drawn as a second robot");
  app.add_option("--validation", validation_path,
                 "Output of `stairplan validate --json`: the violations to mark (default: plan.json's own)");
  app.add_option("--html", html, "The page to write")->required();
  app.add_option("--frame-period", settings.frame_period, "How often the plan's robot is posed [s] (default 0.04)");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("view", [&] {
    if (ViewerBundleJs().empty()) {
      throw BadInput("this stairplan was built without three.js: run scripts/setup.sh (npm ci in stairplan/planning/viewer) and rebuild");
    }
    const std::string text = ReadText(path, "plan file");
    const PlanFile file = ReadPlanJson(text, path);
    const nlohmann::json plan_json = ParseJson(text, path);
    const RobotModel robot = LoadPlanRobot(file, robot_path);
    nlohmann::json sim, validation;
    if (!sim_path.empty()) sim = ParseJson(ReadText(sim_path, "simulation output"), sim_path);
    if (!validation_path.empty()) validation = ParseJson(ReadText(validation_path, "validation report"), validation_path);
    const nlohmann::json scene = BuildViewerScene(robot, file, {&plan_json, path},
                                                  {validation_path.empty() ? nullptr : &validation, validation_path},
                                                  {sim_path.empty() ? nullptr : &sim, sim_path}, settings);
    WriteFileAtomically(html, ViewerPageHtml(scene, ViewerBundleJs()));
    std::cerr << "stairplan view: " << html << ": " << scene["title"].get<std::string>() << "; "
              << scene["frames"]["t"].size() << " frames" << (sim_path.empty() ? "" : " and a simulated run") << "\n";
    return kExitOk;
  });
}

const CommandRegistrar kViewRegistrar({"view", "write a 3D viewer page (HTML) of a plan.json and its MuJoCo run", RunView});

}  // namespace
}  // namespace stairplan::cli
