// `stairplan plan`: plan a traversal of a staircase and write plan.json and plan.svg.
#include <chrono>
#include <iostream>
#include <optional>

#include "geometry/footfall.h"
#include "geometry/footfall_stairs.h"
#include "geometry/point_cloud.h"
#include "geometry/stair_perception.h"
#include "geometry/stair_spec_yaml.h"
#include "planning/cli/cli_common.h"
#include "planning/cli/stair_flags.h"
#include "planning/plan_pipeline.h"
#include "planning/plan_json.h"
#include "planning/plan_svg.h"
#include "planning/step/paper_crawl.h"

namespace stairplan::cli {
namespace {

struct PlanOptions {
  std::string robot;
  RobotFlags robot_flags;
  StairFlags stairs;
  std::string facing = "forward";
  std::string planner = "crawl";
  std::string body = "path";
  std::optional<int> horizon;
  std::string nlp;
  std::string cloud;
  std::string footfalls;
  int staircase = 1;
  std::string out = "stairplan-out";
  std::vector<std::string> set;
  bool json = false;
};

void AddOptions(CLI::App& app, PlanOptions& o) {
  app.add_option("--robot", o.robot, "Robot URDF file (default: the built-in stairbot)");
  AddRobotFlags(app, o.robot_flags);
  AddStairFlags(app, o.stairs);
  app.add_option("--facing", o.facing, "forward or backward, default forward");
  app.add_option("--body", o.body,
                 "path: quasi-static COM path (default); qp: the receding-horizon body QP");
  app.add_option("--horizon", o.horizon, "Knots of the body QP's horizon, 25 ms apart (implies --body qp; default 40)");
  app.add_option("--nlp", o.nlp, "Refine the QP body with the exact NLP: ipopt or nlopt (implies --body qp)");
  app.add_option("--cloud", o.cloud,
                 "Plan on the stairs perceived in this point cloud (PLY, PCD or XYZ; the stairs flags are ignored)");
  app.add_option("--footfalls", o.footfalls,
                 "Plan on a staircase found in this footfall CSV (t,leg,x,y,z), traversed as it was walked; "
                 "--nosing gives the overhang footfalls cannot see (default 0), the other stairs flags are ignored");
  app.add_option("--staircase", o.staircase, "Which staircase of --footfalls, in walking order (default 1)")
      ->check(CLI::PositiveNumber);
  app.add_option("--planner", o.planner,
                 "crawl: the step planner picks the cadence, feet at step-region centres (default); "
                 "step: the step planner's own footsteps; "
                 "paper, paper-alt: the 2012 paper's crawl, cases 1 and 2 (seed 003; climbing only)");
  app.add_option("--out", o.out, "Output directory for plan.json and plan.svg (default ./stairplan-out)");
  app.add_flag("--json", o.json, "Print the plan JSON on stdout instead of the summary");
  app.add_option("--set", o.set, "Override a body planner setting, body.NAME=VALUE (e.g. body.stability_margin=0.03)");
}

// --set body.NAME=VALUE: the body planner's settings by their field names.
void ApplySettings(const std::vector<std::string>& assignments, PipelineOptions& options) {
  for (const std::string& a : assignments) {
    const std::size_t eq = a.find('=');
    const std::string prefix = "body.";
    if (eq == std::string::npos || a.compare(0, prefix.size(), prefix) != 0) {
      throw BadInput("--set: expected body.NAME=VALUE (got '" + a + "')");
    }
    double value = 0.0;
    try {
      std::size_t used = 0;
      value = std::stod(a.substr(eq + 1), &used);
      if (used != a.size() - eq - 1) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      throw BadInput("--set: '" + a.substr(eq + 1) + "' is not a number (in '" + a + "')");
    }
    try {
      options.body_qp.Set(a.substr(prefix.size(), eq - prefix.size()), value);
      options.body_qp.Validate();
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--set: body.") + e.what());
    }
  }
}

double MicrosSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

void PrintSummary(const Plan& plan, const Staircase& stairs, const std::string& out) {
  int in_region = 0;
  for (const Footstep& f : plan.footsteps) in_region += f.in_step_region ? 1 : 0;
  std::cout << "stairplan plan: " << plan.robot_name << " " << ToString(stairs.direction()) << " "
            << stairs.steps() << " steps (rise " << stairs.spec().rise << " m, run " << stairs.spec().run
            << " m), facing " << ToString(plan.facing) << "\n"
            << "  status:    " << ToString(plan.status) << (plan.status_reason.empty() ? "" : " (" + plan.status_reason + ")") << "\n"
            << "  gait:      " << plan.gait << ", cadence " << plan.cadence_s << " s\n"
            << "  footsteps: " << plan.footsteps.size() << " (" << in_region << " inside step regions)\n"
            << "  duration:  " << plan.duration() << " s\n"
            << "  wrote:     " << out << "/plan.json, " << out << "/plan.svg\n";
}

void SetBodyOptions(const PlanOptions& o, PipelineOptions& options) {
  if (o.body != "path" && o.body != "qp") throw BadInput("--body: must be 'path' or 'qp' (got '" + o.body + "')");
  if (!o.nlp.empty() && o.nlp != "ipopt" && o.nlp != "nlopt") {
    throw BadInput("--nlp: must be 'ipopt' or 'nlopt' (got '" + o.nlp + "')");
  }
  if (o.horizon && (*o.horizon < 4 || *o.horizon > 400)) throw BadInput("--horizon: must be from 4 to 400 knots");
  const bool qp = o.body == "qp" || o.horizon || !o.nlp.empty();
  options.body = qp ? BodySource::kRecedingHorizonQp : BodySource::kQuasiStaticPath;
  if (o.horizon) options.body_qp.knots = *o.horizon;
  options.body_nlp = o.nlp;
}

// Staircase `index` (1-based) of those a footfall log walked, as the YAML `footfalls --stairs-out`
// writes it.
Staircase FootfallStaircaseAt(const std::string& path, int index, double nosing) {
  const std::vector<FootfallStaircase> found = StairsFromFootfalls(ReadFootfallCsv(path));
  if (index > static_cast<int>(found.size())) {
    throw NoSolution(path + ": --staircase " + std::to_string(index) + ": the footfalls walked " +
                     std::to_string(found.size()) + " staircases");
  }
  const FootfallStaircase& s = found[static_cast<std::size_t>(index - 1)];
  try {
    return s.model.ToStaircase(s.traversal, nosing);
  } catch (const std::invalid_argument& e) {
    throw NoSolution(path + ": staircase " + std::to_string(index) + " cannot be planned on: " + e.what());
  }
}

// The stairs and their constrained map as perceived from a cloud, in the stairs' own frame.
struct CloudStairs {
  Staircase stairs;
  ConstrainedMap map;
  nlohmann::json fitted;  // the tracker's model, its residuals, and how to place the plan in the world
};

CloudStairs PerceiveCloud(const std::string& path, const StairFlags& flags, Facing facing) {
  StairPerceptionSettings settings;
  settings.regions.travel = flags.direction ? ParseDirection(*flags.direction, "--direction") : TravelDirection::kUp;
  settings.regions.facing = facing;
  const StairPerception seen = PerceiveStairs(ReadPointCloud(path), settings);
  if (!seen.stairs) throw NoSolution(path + ": no stairs found: " + seen.fit.reason);
  const StairModel& m = seen.fit.model;
  const Eigen::Vector3d origin = m.StairToWorld(Eigen::Vector3d::Zero(), settings.regions.travel);
  nlohmann::json fitted = {{"steps", m.steps},
                           {"rise", m.rise},
                           {"run", m.run},
                           {"width", m.width},
                           {"yaw_rad", m.yaw()},
                           {"level_rms_m", seen.fit.level_rms},
                           {"edge_rms_m", seen.fit.edge_rms},
                           {"point_rms_m", seen.fit.point_rms},
                           {"plan_frame_origin_W", {origin.x(), origin.y(), origin.z()}},
                           {"plan_frame_yaw_rad", m.TravelYaw(settings.regions.travel)}};
  return {seen.stairs->stairs, seen.stairs->map, fitted};
}

void PrintValidation(const PipelineResult& result) {
  if (!result.validated) return;
  const ValidationReport& v = result.validation;
  std::cout << "  validated: " << (v.ok ? "ok" : "VIOLATIONS") << ", min clearance " << v.min_clearance_m * 1000
            << " mm, min stability margin " << v.min_stability_margin_m * 1000 << " mm\n";
  if (!v.violations.empty()) {
    const Violation& first = v.violations.front();
    std::cout << "  first violation: t=" << first.t << " s, " << first.leg << ", " << ToString(first.kind) << " ("
              << first.value << (first.detail.empty() ? "" : ", " + first.detail) << ")\n";
  }
}

// The paper's crawl on the pipeline's map, validated as the pipeline validates.
PipelineResult PaperCrawlResult(const RobotModel& robot, const Staircase& stairs, PipelineOptions options, bool alternate) {
  PaperCrawlSettings settings;
  settings.arrangement = alternate ? CrawlCase::kFrontSwitched : CrawlCase::kRightFirst;
  options.crawl.body.hip_height_fraction = settings.body.hip_height_fraction;
  PipelineResult result;
  result.map = BuildPipelineMap(robot, stairs, options);
  result.plan = PlanPaperCrawl(robot, stairs, result.map, settings);
  if (result.plan.status == PlanStatus::kOk && options.validate) {
    TraversalValidator validator(robot, stairs, result.map, options.validation);
    result.validation = validator.Validate(result.plan);
    result.validated = true;
  }
  return result;
}

int RunPlan(const std::vector<std::string>& args) {
  CLI::App app("Plan a traversal of a staircase; writes plan.json and plan.svg", "plan");
  PlanOptions o;
  AddOptions(app, o);
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("plan", [&] {
    const auto t0 = std::chrono::steady_clock::now();
    PipelineOptions options;
    options.facing = ParseFacing(o.facing);
    const bool paper = o.planner == "paper" || o.planner == "paper-alt";
    if (!o.cloud.empty() && !o.footfalls.empty()) throw BadInput("--footfalls: plans on footfalls or on --cloud, not both");
    if (paper && !o.cloud.empty()) throw BadInput("--planner " + o.planner + ": plans known stairs only, not --cloud");
    try {
      if (!paper) options.footsteps = ParseFootstepSource(o.planner);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    SetBodyOptions(o, options);
    ApplySettings(o.set, options);
    const RobotModel robot = LoadRobot(o.robot, o.robot_flags);
    std::optional<CloudStairs> perceived;
    if (!o.cloud.empty()) perceived = PerceiveCloud(o.cloud, o.stairs, options.facing);
    const Staircase stairs = perceived              ? perceived->stairs
                             : !o.footfalls.empty() ? FootfallStaircaseAt(o.footfalls, o.staircase, o.stairs.nosing.value_or(0.0))
                                                    : ResolveStairs(o.stairs);
    const double load_us = MicrosSince(t0);
    if (perceived) AddPipelineRobotRegions(robot, stairs, options, perceived->map);
    PipelineResult result = paper ? PaperCrawlResult(robot, stairs, options, o.planner == "paper-alt")
                            : perceived ? RunPipelineOnMap(robot, stairs, perceived->map, options)
                                        : RunPipeline(robot, stairs, options);
    Plan& plan = result.plan;
    plan.timing_us.insert(plan.timing_us.begin(), {perceived ? "perceive" : "load", load_us});
    nlohmann::json json = PlanToJson(plan, stairs, result.map);
    if (result.validated) json["validation"] = ValidationToJson(result.validation);
    if (perceived) json["fitted"] = perceived->fitted;
    MakeOutputDir(o.out, "--out");
    WriteFileAtomically(o.out + "/plan.json", json.dump(2) + "\n");
    WriteFileAtomically(o.out + "/plan.svg",
                        PlanToSvg(plan, stairs, result.map, result.validated ? &result.validation : nullptr));
    if (o.json) {
      std::cout << json.dump(2) << "\n";
    } else {
      PrintSummary(plan, stairs, o.out);
      PrintValidation(result);
    }
    const bool valid = !result.validated || result.validation.ok;
    return plan.status == PlanStatus::kOk && valid ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kRegistrar({"plan", "plan a traversal of a staircase (plan.json, plan.svg)", RunPlan});

}  // namespace
}  // namespace stairplan::cli
