// `stairplan validate plan.json`: replay a plan through the validator on the stairs it names, or
// with --stairs on other stairs (the true ones of stairs the plan only estimated): there the feet
// land on the true surface under their planned footholds, as `robustness` replays plans.
#include <iostream>

#include "cli/cli_common.h"
#include "cli/stair_flags.h"
#include "cli/validator_flags.h"
#include "stairplan/planning/json_version.h"
#include "stairplan/planning/plan_json.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/pipeline/robustness.h"

namespace stairplan::cli {
namespace {

int RunValidate(const std::vector<std::string>& args) {
  CLI::App app("Validate a plan: reach, joint limits, clearances, stability, step regions, dynamics", "validate");
  std::string path, robot_path;
  StairFlags true_stairs;
  bool json = false;
  app.add_option("plan", path, "plan.json written by `stairplan plan`")->required();
  app.add_option("--robot", robot_path, "Robot URDF (default: the one the plan names)");
  app.add_option("--stairs", true_stairs.file, "Stairs YAML to validate on instead of the plan's own (e.g. the true stairs)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  app.add_flag("--json", json, "Print the validation report as JSON");
  std::vector<std::string> settings;
  app.add_option("--set", settings, "Override a validator setting, validator.NAME=VALUE (e.g. validator.friction=0.5)");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("validate", [&] {
    const PlanFile file = ReadPlanJsonFile(path);
    const RobotModel robot = LoadPlanRobot(file, robot_path, robot_flags);
    const Staircase stairs = true_stairs.file.empty() ? Staircase(file.stairs) : ResolveStairs(true_stairs);
    PipelineOptions options = OptionsForPlan(file.plan);
    for (const std::string& a : settings) ApplyValidatorSetting(a, options.validation);
    const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
    TraversalValidator validator(robot, stairs, map, options.validation);
    const ValidationReport report =
        validator.Validate(true_stairs.file.empty() ? file.plan : PlanOnTrueStairs(file.plan, stairs, map));
    if (json) {
      nlohmann::json out = ValidationToJson(report);
      std::cout << StampVersion(out).dump(2) << "\n";
    } else {
      std::cout << "stairplan validate: " << path << ": " << (report.ok ? "valid" : "INVALID") << ", "
                << report.samples << " instants, min clearance " << report.min_clearance_m * 1000
                << " mm, min stability margin " << report.min_stability_margin_m * 1000 << " mm\n";
      std::cout << "  " << DynamicsSummary(report) << "\n";
      for (const Violation& v : report.violations) {
        std::cout << "  t=" << v.t << " s  " << v.leg << "  " << ToString(v.kind) << "  " << v.value;
        if (v.t_worst != v.t) std::cout << "  (worst " << v.worst << " at t=" << v.t_worst << " s)";
        std::cout << (v.detail.empty() ? "" : "  " + v.detail) << "\n";
      }
    }
    return report.ok ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kValidateRegistrar({"validate", "replay a plan.json and check it (exit 3 on violations)", RunValidate});

}  // namespace
}  // namespace stairplan::cli
