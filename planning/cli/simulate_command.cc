// `stairplan simulate plan.json`: execute a plan in MuJoCo on the stairs it names and print the
// physics outcome as JSON (exit 0 when the robot got there cleanly, 3 when it did not).
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "planning/cli/cli_common.h"
#include "planning/plan_json_reader.h"
#include "planning/simulation/plan_executor.h"
#include "planning/simulation/sim_frame_svg.h"
#include "planning/simulation/sim_outcome_json.h"

namespace stairplan::cli {
namespace {

// The base against the plan over time, one row per recorded frame.
std::string TraceCsv(const SimulationOutcome& outcome) {
  std::ostringstream csv;
  csv << "t,x,y,z,roll,pitch,yaw,plan_x,plan_y,plan_z,plan_pitch,stance\n";
  for (const SimFrame& f : outcome.frames) {
    csv << f.t << "," << f.base_W.x() << "," << f.base_W.y() << "," << f.base_W.z() << "," << f.base_rpy.x() << ","
        << f.base_rpy.y() << "," << f.base_rpy.z() << "," << f.planned_W.x() << "," << f.planned_W.y() << ","
        << f.planned_W.z() << "," << f.planned_pitch << ",";
    for (bool s : f.stance) csv << (s ? 'S' : '-');
    csv << "\n";
  }
  return csv.str();
}

int RunSimulate(const std::vector<std::string>& args) {
  CLI::App app("Execute a plan in MuJoCo and report what happened (JSON)", "simulate");
  std::string path, robot_path, frames_dir, out, trace;
  std::vector<std::string> overrides;
  double frame_ms = 100.0, friction = 0.8;
  app.add_option("plan", path, "plan.json written by `stairplan plan`")->required();
  app.add_option("--robot", robot_path, "Robot URDF (default: the one the plan names)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  app.add_option("--video-frames", frames_dir, "Write an SVG side view every --frame-ms into this directory");
  app.add_option("--frame-ms", frame_ms, "Interval between frames [ms] (default 100)")->check(CLI::Range(1.0, 10000.0));
  app.add_option("--friction", friction, "Sliding friction of every contact (default 0.8)")->check(CLI::Range(0.0, 10.0));
  app.add_option("--out", out, "Also write the JSON result to this file");
  app.add_option("--set", overrides,
                 "Override a simulation setting, name=value (e.g. kp_per_kg=10; time_scale=3 replays 3x slower than planned)");
  app.add_option("--trace", trace, "Write a CSV of the base (measured and planned) every --frame-ms");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("simulate", [&] {
    const PlanFile file = ReadPlanJsonFile(path);
    const RobotModel robot = LoadPlanRobot(file, robot_path, robot_flags);
    const Staircase stairs(file.stairs);
    if (!frames_dir.empty()) MakeOutputDir(frames_dir, "--video-frames");
    SimSettings settings;
    settings.world.friction = friction;
    settings.frame_interval = frames_dir.empty() && trace.empty() ? 0.0 : frame_ms / 1000.0;
    for (const std::string& o : overrides) {
      const std::size_t eq = o.find('=');
      double value = 0.0;
      try {
        value = std::stod(o.substr(eq == std::string::npos ? o.size() : eq + 1));
      } catch (const std::exception&) {
        throw BadInput("--set: expected name=value (got '" + o + "')");
      }
      try {
        settings.Set(o.substr(0, eq), value);
        settings.Validate();
      } catch (const std::invalid_argument& e) {
        throw BadInput(std::string("--set: ") + e.what());
      }
    }
    Plan plan = file.plan;
    plan.facing = file.facing;
    const SimulationOutcome outcome = Simulate(robot, stairs, plan, settings);
    nlohmann::json json = SimulationToJson(outcome);
    json["plan"] = path;
    json["robot"] = robot.name();
    if (!trace.empty()) WriteFileAtomically(trace, TraceCsv(outcome));
    for (std::size_t i = 0; i < outcome.frames.size() && !frames_dir.empty(); ++i) {
      std::ostringstream name;
      name << frames_dir << "/frame_" << std::setw(5) << std::setfill('0') << i << ".svg";
      WriteFileAtomically(name.str(), SimFrameSvg(outcome.frames[i], stairs, plan));
    }
    if (!frames_dir.empty()) json["frames"] = outcome.frames.size();
    const std::string text = json.dump(2) + "\n";
    if (!out.empty()) WriteFileAtomically(out, text);
    std::cout << text;
    std::cerr << "stairplan simulate: " << path << ": " << ToString(outcome.status)
              << (outcome.Passed() ? "" : " (" + outcome.FirstCause() + ")") << "; " << outcome.landings.size()
              << " landings, max error " << outcome.MaxLandingError() * 1000 << " mm; peak torque "
              << outcome.max_torque_ratio * 100 << "% of the limit; time_scale " << outcome.time_scale
              << ", plan ZMP margin " << outcome.plan_zmp_margin_m * 1000 << " mm; real-time factor "
              << outcome.real_time_factor << "\n";
    return outcome.Passed() ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kRegistrar({"simulate", "execute a plan.json in MuJoCo (exit 3 when the robot fails)", RunSimulate});

}  // namespace
}  // namespace stairplan::cli
