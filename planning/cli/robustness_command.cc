// `stairplan robustness`: open-loop execution of a nominal plan on stairs with per-step rise and
// run errors, against replanning on the true stairs (the 2012 paper's dW/dH analysis).
#include <algorithm>
#include <iostream>

#include <nlohmann/json.hpp>

#include "geometry/field_error.h"
#include "planning/cli/cli_common.h"
#include "planning/json_version.h"
#include "planning/cli/stair_flags.h"
#include "planning/robustness.h"

namespace stairplan::cli {
namespace {

int RunRobustness(const std::vector<std::string>& args) {
  CLI::App app("Open-loop robustness of a plan to per-step stair errors, against replanning", "robustness");
  std::string robot_path, facing = "forward";
  StairFlags stairs;
  RobustnessSettings settings;
  bool json = false;
  app.add_option("--robot", robot_path, "Robot URDF (default: the built-in stairbot)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  AddStairFlags(app, stairs);
  app.add_option("--facing", facing, "forward or backward, default forward");
  app.add_option("--sigma-rise", settings.sigma_rise, "Std. dev. of each rise's error [m] (default 0.005)");
  app.add_option("--sigma-run", settings.sigma_run, "Std. dev. of each run's error [m] (default 0.01)");
  app.add_option("--trials", settings.trials, "Perturbed staircases (default 20)");
  app.add_option("--seed", settings.seed, "Random seed (default 1)");
  app.add_flag("--json", json, "Print the report as JSON");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("robustness", [&] {
    const Staircase nominal = ResolveStairs(stairs);
    PipelineOptions options;
    options.facing = ParseFacing(facing);
    options.validation.time_step = 0.05;
    RobustnessReport report;
    try {
      report = EvaluateRobustness(LoadRobot(robot_path, robot_flags), nominal.spec(), options, settings);
    } catch (const FieldError& e) {
      std::string flag = e.field();
      std::replace(flag.begin(), flag.end(), '_', '-');
      throw BadInput("--" + flag + ": " + e.problem());
    }
    if (json) {
      nlohmann::json out = {{"trials", report.trials}, {"nominal_valid", report.nominal_valid == 1},
                            {"open_loop_ok", report.open_loop_ok}, {"replanned_ok", report.replanned_ok},
                            {"worst_cumulative_run_error_m", report.worst_cumulative_run_error}};
      std::cout << StampVersion(out).dump(2) << "\n";
    } else {
      std::cout << "stairplan robustness: nominal plan " << (report.nominal_valid ? "valid" : "INVALID") << "; over "
                << report.trials << " perturbed staircases (sigma rise " << settings.sigma_rise << " m, run "
                << settings.sigma_run << " m): open loop " << report.open_loop_ok << "/" << report.trials
                << " valid, replanned " << report.replanned_ok << "/" << report.trials
                << " valid; worst cumulative run error " << report.worst_cumulative_run_error << " m\n";
    }
    return kExitOk;
  });
}

const CommandRegistrar kRegistrar({"robustness", "open-loop plan on perturbed stairs vs replanning", RunRobustness});

}  // namespace
}  // namespace stairplan::cli
