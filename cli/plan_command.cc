// `stairplan plan`: plan a traversal of a staircase and write plan.json and plan.svg.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <optional>

#include "stairplan/perception/footfall.h"
#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/perception/footfall_track.h"
#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/stair_mode_engagement.h"
#include "stairplan/perception/point_cloud.h"
#include "stairplan/perception/stair_perception.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "cli/cli_common.h"
#include "cli/stair_flags.h"
#include "cli/validator_flags.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/plan_json.h"
#include "stairplan/planning/plan_svg.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/stair_approach_json.h"

namespace stairplan::cli {
namespace {

struct PlanOptions {
  std::string robot;
  RobotFlags robot_flags;
  StairFlags stairs;
  std::string facing = "forward";
  std::string planner = "crawl";
  std::string gait = "crawl";
  std::string crawl_sequence;  // empty: CrawlSettings' default
  std::string body;            // empty: PipelineOptions' default
  std::optional<int> horizon;
  std::string nlp;
  std::string cloud;
  std::string footfalls;
  int staircase = 1;
  std::string out = "stairplan-out";
  std::vector<std::string> set;
  std::vector<double> start;
  std::optional<double> engage_distance;
  bool align_start = false;
  bool json = false;
};

void AddOptions(CLI::App& app, PlanOptions& o) {
  app.add_option("--robot", o.robot, "Robot URDF file (default: the built-in stairbot)");
  AddRobotFlags(app, o.robot_flags);
  AddStairFlags(app, o.stairs);
  app.add_option("--facing", o.facing, "forward or backward, default forward");
  app.add_option("--body", o.body,
                 "qp: the receding-horizon body optimisation with its leg, support and clearance rows (default; "
                 "--set body.stance_rows=0: without the leg rows); path: the quasi-static COM path with its "
                 "posture retries, a baseline (the paper's crawls always plan their own)");
  app.add_option("--horizon", o.horizon, "Knots of the body QP's horizon, 50 ms apart (implies --body qp; default 20)");
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
  app.add_option("--gait", o.gait,
                 "crawl: four feet down for 0.6 s between swings (0.8 s descending), balanced over the support "
                 "polygon (default); walk: the crawl's footholds and swings with 0.2 s four-feet phases, about 40 % "
                 "faster, judged by the validator's dynamic check; trot: the same footholds, the diagonal pairs "
                 "swinging together for 0.25 s with 0.15 s four-feet phases, the body's ZMP on the standing diagonal, "
                 "judged by the dynamic check; auto: the fastest of the trot, the walk and the crawl whose plan validates (--planner crawl only)");
  app.add_option("--crawl-sequence", o.crawl_sequence,
                 "Order of the crawl's swings along the travel: lateral (each side's trailing then leading leg; "
                 "default; where no body is found, leading-first is tried too), leading-first (each side's leading "
                 "then trailing leg) or pairs (trailing pair then leading pair, the 2012 paper's)");
  app.add_option("--out", o.out, "Output directory for plan.json and plan.svg (default ./stairplan-out)");
  app.add_option("--start", o.start,
                 "X,Y,YAW: the robot's tracked pose; stair mode is judged there and the robot turns and moves to the "
                 "alignment pose the plan starts from. In the cloud's or the footfall log's world with --cloud or "
                 "--footfalls, else in the stairs' own frame (x along the travel from the first riser, y left) "
                 "[m, m, rad]. Default: with --footfalls where stair mode engaged along the log's track, else at the "
                 "alignment pose")
      ->expected(3)
      ->delimiter(',');
  app.add_option("--engage-distance", o.engage_distance, "Stair mode engages this close to the flight [m] (default 1.0)");
  app.add_flag("--align-start", o.align_start,
               "Start at the alignment pose, the feet in the robot's standing stance there (default: on the crawl's "
               "footholds nearest under the hips; plan.json's alignment.plan_start_offset_m says how far that is)");
  app.add_flag("--json", o.json, "Print the plan JSON on stdout instead of the summary");
  app.add_option("--set", o.set,
                 "Override a body planner or validator setting, body.NAME=VALUE or validator.NAME=VALUE (e.g. "
                 "body.stability_margin=0.03, validator.friction=0.5)");
}

// --set body.NAME=VALUE / validator.NAME=VALUE: the body planner's or the validator's settings by
// their field names.
void ApplySettings(const std::vector<std::string>& assignments, PipelineOptions& options) {
  for (const std::string& a : assignments) {
    const std::size_t eq = a.find('=');
    const bool validator = a.rfind("validator.", 0) == 0;
    const std::string prefix = validator ? "validator." : "body.";
    if (eq == std::string::npos || a.compare(0, prefix.size(), prefix) != 0) {
      throw BadInput("--set: expected body.NAME=VALUE or validator.NAME=VALUE (got '" + a + "')");
    }
    if (validator) {
      ApplyValidatorSetting(a, options.validation);
      continue;
    }
    const double value = SettingValue(a);
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

// The receding horizon's cycles that sent the robot through a row they could not mend in time.
void PrintRelaxedCycles(const std::vector<BodyCycleStats>& cycles) {
  const RelaxedCycles relaxed = SummariseRelaxed(cycles);
  if (relaxed.count == 0) return;
  std::cout << "  relaxed:   " << relaxed.count << " cycles executed a knot keeping part of a broken row (first t="
            << relaxed.first_t << " s, at most " << relaxed.most << " of it)\n";
}

void PrintSummary(const Plan& plan, const Staircase& stairs, const std::string& out) {
  int in_region = 0;
  for (const Footstep& f : plan.footsteps) in_region += f.in_step_region ? 1 : 0;
  std::cout << "stairplan plan: " << plan.robot_name << " " << ToString(stairs.direction()) << " "
            << stairs.steps() << " steps (rise " << stairs.spec().rise << " m, run " << stairs.spec().run
            << " m), facing " << ToString(plan.facing) << "\n"
            << "  status:    " << ToString(plan.status) << (plan.status_reason.empty() ? "" : " (" + plan.status_reason + ")") << "\n";
  // Refused before any footstep (a rise no leg can step): nothing was planned to describe.
  if (plan.status != PlanStatus::kOk && plan.footsteps.empty()) {
    std::cout << "  wrote:     " << out << "/plan.json, " << out << "/plan.svg\n";
    return;
  }
  std::cout << "  gait:      " << GaitName(plan.gait) << ", cadence " << plan.cadence_s << " s\n";
  for (const GaitRejection& g : plan.rejected_gaits) std::cout << "  not the " << ToString(g.gait) << ": " << g.reason << "\n";
  std::cout
            << "  footsteps: " << plan.footsteps.size() << " (" << in_region << " inside step regions)\n"
            << "  duration:  " << plan.duration() << " s; flight " << FlightDuration(plan)
            << " s from the first liftoff to the last touchdown, " << TravelSpeed(plan) << " m/s\n";
  PrintRelaxedCycles(plan.body_cycles);
  std::cout << "  wrote:     " << out << "/plan.json, " << out << "/plan.svg\n";
}

void SetBodyOptions(const PlanOptions& o, PipelineOptions& options) {
  if (!o.body.empty() && o.body != "path" && o.body != "qp") {
    throw BadInput("--body: must be 'path' or 'qp' (got '" + o.body + "')");
  }
  if (!o.nlp.empty() && o.nlp != "ipopt" && o.nlp != "nlopt") {
    throw BadInput("--nlp: must be 'ipopt' or 'nlopt' (got '" + o.nlp + "')");
  }
  if (o.horizon && (*o.horizon < 4 || *o.horizon > 400)) throw BadInput("--horizon: must be from 4 to 400 knots");
  const bool qp = o.body == "qp" || o.horizon || !o.nlp.empty();
  if (qp && IsPaperCrawl(options.footsteps)) {
    throw BadInput("--body qp: the paper's crawls plan their own quasi-static body path");
  }
  if (qp) options.body = BodySource::kRecedingHorizonQp;
  if (o.body == "path") options.body = BodySource::kQuasiStaticPath;
  if (o.horizon) options.body_qp.knots = *o.horizon;
  options.body_nlp = o.nlp;
}

// Stairs found in the world (a cloud, footfalls): the Staircase planned on, its frame in the world
// and, from footfalls, the robot's pose where stair mode engaged for it along the log's track.
struct WorldStairs {
  Staircase stairs;
  StairFrame frame;
  std::optional<GroundPose> tracked_W;
};

// Staircase `index` (1-based) of those a footfall log walked, as the YAML `footfalls --stairs-out`
// writes it.
WorldStairs FootfallStaircaseAt(const std::string& path, int index, double nosing, const StairModeSettings& mode) {
  const std::vector<Footfall> footfalls = ReadFootfallCsv(path);
  const std::vector<FootfallStaircase> found = StairsFromFootfalls(footfalls);
  if (index > static_cast<int>(found.size())) {
    throw NoSolution(path + ": --staircase " + std::to_string(index) + ": the footfalls walked " +
                     std::to_string(found.size()) + " staircases");
  }
  const FootfallStaircase& s = found[static_cast<std::size_t>(index - 1)];
  try {
    WorldStairs w{s.model.ToStaircase(s.traversal, nosing), {s.model, s.traversal, nosing}, std::nullopt};
    std::vector<StairModel> known;
    for (const FootfallStaircase& f : found) known.push_back(f.model);
    const std::vector<GroundPose> track = TrackFromFootfalls(footfalls);
    if (!track.empty()) w.tracked_W = EngagementAlongTrack(track, known, index - 1, mode).pose;
    return w;
  } catch (const std::invalid_argument& e) {
    throw NoSolution(path + ": staircase " + std::to_string(index) + " cannot be planned on: " + e.what());
  }
}

// The stairs and their constrained map as perceived from a cloud, in the stairs' own frame.
struct CloudStairs {
  Staircase stairs;
  ConstrainedMap map;
  StairFrame frame;  // the stairs' frame in the cloud's world
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
                           {"uncertainty_m", m.uncertainty},
                           {"plan_frame_origin_W", {origin.x(), origin.y(), origin.z()}},
                           {"plan_frame_yaw_rad", m.TravelYaw(settings.regions.travel)}};
  return {seen.stairs->stairs, seen.stairs->map, {m, settings.regions.travel, settings.regions.nosing}, fitted};
}

void PrintValidation(const PipelineResult& result) {
  if (!result.validated) return;
  const ValidationReport& v = result.validation;
  std::cout << "  validated: " << (v.ok ? "ok" : "VIOLATIONS") << ", min clearance " << v.min_clearance_m * 1000
            << " mm, min stability margin " << v.min_stability_margin_m * 1000 << " mm\n";
  std::cout << "  " << DynamicsSummary(v) << "\n";
  if (!v.violations.empty()) {
    const Violation& first = v.violations.front();
    std::cout << "  first violation: t=" << first.t << " s, " << first.leg << ", " << ToString(first.kind) << " ("
              << first.value << (first.detail.empty() ? "" : ", " + first.detail) << ")\n";
  }
}

// --engage-distance: stair mode's threshold (the release distance kept at least as far).
void SetStairMode(const PlanOptions& o, StairModeSettings& mode) {
  if (!o.engage_distance) return;
  mode.engage_distance = *o.engage_distance;
  mode.release_distance = std::max(mode.release_distance, mode.engage_distance);
  try {
    mode.Validate();
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("--engage-distance: ") + e.what());
  }
}

// The robot's pose in the plan's frame: --start (in `world` when the stairs were found there), else
// where stair mode engaged along the footfall track, else none (at the alignment pose).
void SetRobotPose(const std::vector<double>& start, const StairFrame* world, const std::optional<GroundPose>& tracked_W,
                  PipelineOptions& options) {
  if (!start.empty()) {
    try {
      options.robot_pose = RobotPoseInPlanFrame(start, world);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--start: ") + e.what());
    }
    options.robot_pose_source = RobotPoseSource::kGiven;
    return;
  }
  if (!tracked_W || !world) return;
  options.robot_pose = world->ToStair(*tracked_W);
  options.robot_pose_source = RobotPoseSource::kFootfallTrack;
}

void PrintApproach(const StairApproach& a, const Plan& plan) {
  if (!a.alignment.found) {
    std::cout << "  alignment: none (" << a.alignment.reason << ")\n";
    return;
  }
  const StartOffset offset = PlanStartOffset(plan, a.alignment);
  std::cout << "  alignment: x " << a.alignment.position.x() << " m (" << a.alignment.standoff
            << " m before the first edge), yaw " << a.alignment.yaw << " rad; the plan starts " << offset.distance * 1000
            << " mm from it\n"
            << "  stair mode: " << (a.stair_mode.engaged ? "engaged" : "NOT engaged") << ", robot " << a.stair_mode.distance
            << " m from the flight (engages within " << a.stair_mode.engage_distance << " m)"
            << (a.robot_known() ? "" : ", taken to be at the alignment pose") << "\n";
}

// Seed 001 [0043]: the operator is warned when stair mode is asked for out of the stairs' range.
void WarnStairModeOff(const StairApproach& a) {
  if (a.stair_mode.engaged) return;
  std::cerr << "stairplan plan: warning: stair mode is not engaged: the robot is " << a.stair_mode.distance
            << " m from the flight and it engages within " << a.stair_mode.engage_distance
            << " m; the robot must first come to the alignment pose (plan.json's alignment)\n";
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
    if (!o.cloud.empty() && !o.footfalls.empty()) throw BadInput("--footfalls: plans on footfalls or on --cloud, not both");
    try {
      options.footsteps = ParseFootstepSource(o.planner);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    if (IsPaperCrawl(options.footsteps) && !o.cloud.empty()) throw BadInput("--planner " + o.planner + ": plans known stairs only, not --cloud");
    try {
      options.gait = ParseGaitChoice(o.gait);
      RequirePlannableGait(options.gait, options.footsteps);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    try {
      if (!o.crawl_sequence.empty()) options.crawl.sequence = ParseCrawlSequence(o.crawl_sequence);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("--") + e.what());
    }
    SetBodyOptions(o, options);
    ApplySettings(o.set, options);
    SetStairMode(o, options.stair_mode);
    options.start_at_alignment = o.align_start;
    const RobotModel robot = LoadRobot(o.robot, o.robot_flags);
    std::optional<CloudStairs> perceived;
    if (!o.cloud.empty()) perceived = PerceiveCloud(o.cloud, o.stairs, options.facing);
    std::optional<WorldStairs> walked;
    if (!o.footfalls.empty()) walked = FootfallStaircaseAt(o.footfalls, o.staircase, o.stairs.nosing.value_or(0.0), options.stair_mode);
    const Staircase stairs = perceived ? perceived->stairs : walked ? walked->stairs : ResolveStairs(o.stairs);
    const StairFrame* world = perceived ? &perceived->frame : walked ? &walked->frame : nullptr;
    SetRobotPose(o.start, world, walked ? walked->tracked_W : std::nullopt, options);
    const double load_us = MicrosSince(t0);
    if (perceived) AddPipelineRobotRegions(robot, stairs, options, perceived->map);
    PipelineResult result = perceived ? RunPipelineOnMap(robot, stairs, perceived->map, options) : RunPipeline(robot, stairs, options);
    Plan& plan = result.plan;
    plan.timing_us.insert(plan.timing_us.begin(), {perceived ? "perceive" : "load", load_us});
    nlohmann::json json = PlanToJson(plan, stairs, result.map);
    if (result.validated) json["validation"] = ValidationToJson(result.validation);
    if (perceived) json["fitted"] = perceived->fitted;
    // The clearances the planners kept: their margins plus the uncertainty of the stairs planned on.
    json["clearance"] = ClearancesToJson(result.clearances);
    json.update(StairApproachToJson(result.approach, plan, world));
    MakeOutputDir(o.out, "--out");
    WriteFileAtomically(o.out + "/plan.json", json.dump(2) + "\n");
    WriteFileAtomically(o.out + "/plan.svg",
                        PlanToSvg(plan, stairs, result.map, result.validated ? &result.validation : nullptr));
    if (o.json) {
      std::cout << json.dump(2) << "\n";
    } else {
      PrintSummary(plan, stairs, o.out);
      PrintValidation(result);
      PrintApproach(result.approach, plan);
    }
    WarnStairModeOff(result.approach);
    const bool valid = !result.validated || result.validation.ok;
    return plan.status == PlanStatus::kOk && valid ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kPlanRegistrar({"plan", "plan a traversal of a staircase (plan.json, plan.svg)", RunPlan});

}  // namespace
}  // namespace stairplan::cli
