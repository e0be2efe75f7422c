// `stairplan robustness`: open-loop execution of a nominal plan on stairs with per-step rise and
// run errors, against replanning on the true stairs (the 2012 paper's dW/dH analysis); with
// --simulate also executed in MuJoCo on the same stairs, answering impacts and not.
#include <algorithm>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "cli/cli_common.h"
#include "stairplan/planning/json_version.h"
#include "cli/stair_flags.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/pipeline/robustness.h"
#include "stairplan/simulation/physics_robustness.h"

namespace stairplan::cli {
namespace {

int RunRobustness(const std::vector<std::string>& args) {
  CLI::App app("Open-loop robustness of a plan to per-step stair errors, against replanning", "robustness");
  std::string robot_path, facing = "forward", stairs_out;
  StairFlags stairs;
  RobustnessSettings settings;
  bool json = false, simulate = false;
  std::optional<double> swing_clearance;
  app.add_option("--robot", robot_path, "Robot URDF (default: the built-in stairbot)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  AddStairFlags(app, stairs);
  app.add_option("--facing", facing, "forward or backward, default forward");
  app.add_option("--sigma-rise", settings.sigma_rise, "Std. dev. of each rise's error [m] (default 0.005)");
  app.add_option("--sigma-run", settings.sigma_run, "Std. dev. of each run's error [m] (default 0.01)");
  app.add_option("--trials", settings.trials, "Perturbed staircases (default 20)");
  app.add_option("--seed", settings.seed, "Random seed (default 1)");
  app.add_flag("--simulate", simulate,
               "Also execute the nominal plan in MuJoCo on each perturbed staircase, with the impact responses and "
               "without; both pass counts are reported");
  app.add_option("--swing-clearance", swing_clearance,
                 "Plan the swings this high over the nosings and at least this far above the higher foothold [m] "
                 "(default: the crawl's 0.06 and 0.05); low swings are where a stair error stubs a toe")
      ->check(CLI::Range(0.0, 0.3));
  app.add_option("--stairs-out", stairs_out,
                 "Write each perturbed staircase to DIR/staircase_K.yaml (K from 0), to replay one with "
                 "`stairplan simulate PLAN --stairs`");
  app.add_flag("--json", json, "Print the report as JSON");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("robustness", [&] {
    const Staircase nominal = ResolveStairs(stairs);
    PipelineOptions options;
    options.facing = ParseFacing(facing);
    options.validation.time_step = 0.05;
    if (swing_clearance) options.crawl.swing.clearance = options.crawl.swing.min_lift = *swing_clearance;
    const RobotModel robot = LoadRobot(robot_path, robot_flags);
    if (!stairs_out.empty()) {
      MakeOutputDir(stairs_out, "--stairs-out");
      const std::vector<StairSpec> perturbed = PerturbedStaircases(nominal.spec(), settings);
      for (std::size_t k = 0; k < perturbed.size(); ++k) {
        WriteFileAtomically(stairs_out + "/staircase_" + std::to_string(k) + ".yaml",
                            StairSpecToYaml(perturbed[k], "perturbed staircase " + std::to_string(k) + " of stairplan robustness"));
      }
    }
    RobustnessReport report;
    PhysicsRobustnessReport physics;
    try {
      report = EvaluateRobustness(robot, nominal.spec(), options, settings);
      if (simulate) {
        physics = EvaluatePhysicsRobustness(robot, nominal.spec(), RunPipeline(robot, nominal, options).plan,
                                            PerturbedStaircases(nominal.spec(), settings));
      }
    } catch (const FieldError& e) {
      std::string flag = e.field();
      std::replace(flag.begin(), flag.end(), '_', '-');
      throw BadInput("--" + flag + ": " + e.problem());
    }
    if (json) {
      nlohmann::json out = {{"trials", report.trials}, {"nominal_valid", report.nominal_valid == 1},
                            {"open_loop_ok", report.open_loop_ok}, {"replanned_ok", report.replanned_ok},
                            {"worst_cumulative_run_error_m", report.worst_cumulative_run_error}};
      if (simulate) {
        out["simulated"] = {{"nominal_ok", physics.nominal_ok == 1}, {"with_responses_ok", physics.with_responses_ok},
                            {"without_responses_ok", physics.without_responses_ok},
                            {"with_responses_fell", physics.with_responses_fell},
                            {"without_responses_fell", physics.without_responses_fell}, {"trips", physics.trips}};
        out["simulated"]["runs"] = nlohmann::json::array();
        for (const PhysicsRobustnessTrial& run : physics.runs) {
          out["simulated"]["runs"].push_back({{"with_responses_failure", run.with_responses},
                                              {"without_responses_failure", run.without_responses},
                                              {"responses", run.responses}});
        }
      }
      std::cout << StampVersion(out).dump(2) << "\n";
    } else {
      std::cout << "stairplan robustness: nominal plan " << (report.nominal_valid ? "valid" : "INVALID") << "; over "
                << report.trials << " perturbed staircases (sigma rise " << settings.sigma_rise << " m, run "
                << settings.sigma_run << " m): open loop " << report.open_loop_ok << "/" << report.trials
                << " valid, replanned " << report.replanned_ok << "/" << report.trials
                << " valid; worst cumulative run error " << report.worst_cumulative_run_error << " m\n";
      if (simulate) {
        std::cout << "  in MuJoCo: nominal " << (physics.nominal_ok ? "passed" : "FAILED") << "; open loop with impact responses "
                  << physics.with_responses_ok << "/" << physics.trials << " passed, without " << physics.without_responses_ok
                  << "/" << physics.trials << " (" << physics.trips << " trips answered); fell " << physics.with_responses_fell
                  << " times with responses, " << physics.without_responses_fell << " without\n";
        for (std::size_t k = 0; k < physics.runs.size(); ++k) {
          const PhysicsRobustnessTrial& run = physics.runs[k];
          if (run.with_responses.empty() && run.without_responses.empty()) continue;
          std::cout << "    staircase " << k << ": with responses (" << run.responses << " carried out) "
                    << (run.with_responses.empty() ? "passed" : run.with_responses) << "; without "
                    << (run.without_responses.empty() ? "passed" : run.without_responses) << "\n";
        }
      }
    }
    return kExitOk;
  });
}

const CommandRegistrar kRobustnessRegistrar({"robustness", "open-loop plan on perturbed stairs vs replanning", RunRobustness});

}  // namespace
}  // namespace stairplan::cli
