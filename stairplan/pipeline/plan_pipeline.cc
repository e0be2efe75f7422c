#include "stairplan/pipeline/plan_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/body/plan_body.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/planning/crawl_planner.h"
#include "stairplan/planning/step/ik_reach_model.h"
#include "stairplan/planning/step/paper_crawl.h"
#include "stairplan/planning/step/step_height.h"
#include "stairplan/planning/step/step_planner_driver.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {
namespace {

double MicrosSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

// Inserts a four-feet phase before every swing that does not overlap the previous one, so the
// COM can move to the next support triangle with all feet down.
void InsertShiftPhases(Plan& plan, double shift) {
  double offset = 0.0, last_touchdown = 0.0;
  for (Footstep& f : plan.footsteps) {
    const double swing = f.t_touchdown - f.t_liftoff;
    f.t_liftoff += offset;
    if (f.t_liftoff >= last_touchdown - 1e-9) {
      offset += shift;
      f.t_liftoff += shift;
    }
    f.t_touchdown = f.t_liftoff + swing;
    last_touchdown = std::max(last_touchdown, f.t_touchdown);
  }
}

Plan StepPlannerPlan(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                     const PipelineOptions& options) {
  const RobotModel& robot = kinematics.robot();
  Plan plan = PlanWithStepPlanner(robot, stairs, map, options.step, std::make_shared<IkReachModel>(kinematics));
  if (plan.status != PlanStatus::kOk) return plan;
  InsertShiftPhases(plan, options.crawl.shift_duration);
  for (Footstep& f : plan.footsteps) {
    f.swing_apex_z = SwingTrajectory(f.from_W, f.position_W, stairs, options.crawl.swing).apex_z();
  }
  if (options.body == BodySource::kRecedingHorizonQp) {
    plan.body.clear();  // the body optimisation's to plan
    return plan;
  }
  const double yaw = options.facing == Facing::kForward ? 0.0 : M_PI;
  BodyPathSettings body = options.crawl.body;
  body.swing = options.crawl.swing;
  plan.body = BodyPathForFootsteps(robot, plan.legs, plan.initial_feet_W, plan.footsteps, yaw, body, &stairs);
  return plan;
}

// The crawl at the cadence the step planner selects, with the controllers' scores recorded.
Plan SelectedCrawlPlan(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                       const PipelineOptions& options) {
  const RobotModel& robot = kinematics.robot();
  const Plan selection = PlanWithStepPlanner(robot, stairs, map, options.step, std::make_shared<IkReachModel>(kinematics));
  // A rise no leg can step rules out every controller whatever its cadence, and any crawl with them.
  if (FirstRiseTooHigh(robot.legs(), map, options.step)) return selection;
  CrawlSettings crawl = options.crawl;
  if (selection.status == PlanStatus::kOk && selection.cadence_s > 0.0) crawl.swing_duration = selection.cadence_s;
  if (options.gait == GaitChoice::kTrot) crawl.swing_duration = options.trot_swing_duration;
  // The body optimisation judges footholds itself (BodyOnFittedLayouts); the crawl's own search
  // judges them by the quasi-static path.
  Plan plan = options.body == BodySource::kRecedingHorizonQp ? PlanCrawlFootholds(robot, stairs, map, crawl)
                                                              : PlanCrawl(robot, stairs, map, crawl);
  // When no controller is admissible everywhere, the crawl keeps its default cadence and the
  // validator has the last word; the controllers' rule-out reasons stay in the plan.
  plan.controllers = selection.controllers;
  plan.selected = selection.status == PlanStatus::kOk ? selection.selected : -1;
  return plan;
}

PaperCrawlSettings PaperSettings(FootstepSource source) {
  PaperCrawlSettings settings;
  settings.arrangement = source == FootstepSource::kPaperCrawlAlternate ? CrawlCase::kFrontSwitched : CrawlCase::kRightFirst;
  return settings;
}

// The options as the footstep source plans with them: the paper's crawl stands at its own
// posture, so the map's robot regions and the alignment stance are made for that one.
PipelineOptions ForFootstepSource(const PipelineOptions& given) {
  PipelineOptions options = given;
  if (!IsPaperCrawl(options.footsteps)) return options;
  options.body = BodySource::kQuasiStaticPath;  // its body is part of the paper's design
  options.crawl.body.hip_height_fraction = PaperSettings(options.footsteps).body.hip_height_fraction;
  return options;
}

Plan FootstepPlan(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                  const PipelineOptions& options) {
  switch (options.footsteps) {
    case FootstepSource::kStepPlanner:
      return StepPlannerPlan(kinematics, stairs, map, options);
    case FootstepSource::kPaperCrawl:
    case FootstepSource::kPaperCrawlAlternate:
      return PlanPaperCrawl(kinematics.robot(), stairs, map, PaperSettings(options.footsteps));
    case FootstepSource::kSelectedCrawl:
      break;
  }
  return SelectedCrawlPlan(kinematics, stairs, map, options);
}

bool SameFootholds(const Plan& a, const Plan& b) {
  if (a.initial_feet_W != b.initial_feet_W || a.footsteps.size() != b.footsteps.size()) return false;
  for (std::size_t i = 0; i < a.footsteps.size(); ++i) {
    if (a.footsteps[i].leg != b.footsteps[i].leg || a.footsteps[i].position_W != b.footsteps[i].position_W) return false;
  }
  return true;
}

// `footsteps` judged without a body: it lands a foot on another (CrowdedTouchdowns()).
Plan CrowdedLayout(Plan footsteps, const TouchdownCrowding& crowding) {
  char text[160];
  std::snprintf(text, sizeof(text), "footholds: %d touchdown%s on a foot that still stands (the first at t=%.3f s, %s on %s)",
                crowding.touchdowns, crowding.touchdowns == 1 ? "" : "s", crowding.first_t, crowding.leg.c_str(),
                crowding.onto.c_str());
  footsteps.status = PlanStatus::kInfeasible;
  footsteps.status_reason = text;
  return footsteps;
}

// The body optimisation on the crawl's footholds. Which tread each foot takes, and in which order
// the legs swing, are choices the continuous optimisation cannot make, and only it can tell whether
// a body exists on them: where it finds none on the footholds given, the crawl's other layouts
// fitted to the robot are planned in turn, then all of them in the other lateral order, up to
// body_layouts plans in all, and the first on which it finds a body is the plan. A layout that
// lands a foot on another has no body (the feet would stand in each other): the search passes it
// without planning one.
Plan BodyOnFittedLayouts(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                         const Plan& footsteps, const PipelineOptions& options, const std::optional<Eigen::Vector2d>& standing) {
  const RobotModel& robot = kinematics.robot();
  // Where other layouts may follow, a failing first layout is planned only to its first failure,
  // as they are: the rest of a plan that fails is of no use but to count its failures.
  const bool search = options.footsteps == FootstepSource::kSelectedCrawl && options.body_layouts > 0;
  const TouchdownCrowding crowding = search ? CrowdedTouchdowns(robot, footsteps) : TouchdownCrowding{};
  Plan first = crowding.touchdowns > 0 ? CrowdedLayout(footsteps, crowding)
                                       : PlanBody(kinematics, stairs, map, footsteps, options.body_qp, standing, search);
  if (first.status == PlanStatus::kOk || !search) return first;
  const auto t_layouts = std::chrono::steady_clock::now();
  CrawlSettings crawl = options.crawl;
  crawl.swing_duration = footsteps.cadence_s;
  std::vector<CrawlSettings> layouts = {crawl};
  for (const CrawlSettings& layout : FittedLayouts(robot, stairs, map, crawl)) layouts.push_back(layout);
  const CrawlSequence other = OtherLateralOrder(crawl.sequence);
  int tried = 0;
  // Where the first layout had no body planned, why the first one planned failed.
  std::string next_reason;
  const int orders = other == crawl.sequence ? 1 : 2;
  for (int o = 0; o < orders; ++o) {
    for (std::size_t i = 0; i < layouts.size() && tried < options.body_layouts; ++i) {
      CrawlSettings ordered = layouts[i];
      ordered.sequence = o == 0 ? crawl.sequence : other;
      Plan candidate = PlanCrawlFootholds(robot, stairs, map, ordered);
      if (candidate.status != PlanStatus::kOk || SameFootholds(candidate, footsteps) ||
          CrowdedTouchdowns(robot, candidate).touchdowns > 0) {
        continue;
      }
      ++tried;
      candidate.gait = footsteps.gait;
      candidate.controllers = footsteps.controllers;
      candidate.selected = footsteps.selected;
      Plan bodied = PlanBody(kinematics, stairs, map, std::move(candidate), options.body_qp, standing, true);
      if (bodied.status != PlanStatus::kOk) {
        if (crowding.touchdowns > 0 && next_reason.empty()) next_reason = bodied.status_reason;
        continue;
      }
      bodied.timing_us.emplace_back("other_layouts", MicrosSince(t_layouts));
      return bodied;
    }
  }
  if (!next_reason.empty()) first.status_reason += "; on the next layout, " + next_reason;
  if (tried > 0) {
    first.status_reason += "; none on " + std::to_string(tried) + " other foothold layout" + (tried > 1 ? "s or orders" : " or order") + " either";
  }
  first.timing_us.emplace_back("other_layouts", MicrosSince(t_layouts));
  return first;
}

// Rejected for body jumps, legs at their reach or limits or on the stairs alone (BodyPosture).
bool IsNearMiss(const ValidationReport& report) {
  return std::all_of(report.violations.begin(), report.violations.end(), [](const Violation& v) {
    return v.kind == ViolationKind::kBodyAcceleration || v.kind == ViolationKind::kJointLimits ||
           v.kind == ViolationKind::kOutOfReach || v.kind == ViolationKind::kStairCollision;
  });
}

// A near miss whose body jumps and whose legs all reach their footholds (RunPipeline).
bool IsJumpingNearMiss(const ValidationReport& report) {
  const auto has = [&report](ViolationKind kind) {
    return std::any_of(report.violations.begin(), report.violations.end(), [kind](const Violation& v) { return v.kind == kind; });
  };
  return IsNearMiss(report) && has(ViolationKind::kBodyAcceleration) && !has(ViolationKind::kOutOfReach);
}

void AddRobotRegions(const RobotKinematics& kinematics, const Staircase& stairs, const PipelineOptions& options,
                     ConstrainedMap& map) {
  if (!options.robot_regions) return;
  const RobotCollisionModel collision(kinematics);
  RobotRegionSettings regions = options.regions;
  regions.hip_height_fraction = options.crawl.body.hip_height_fraction;  // the posture the plan will use
  AddRobotCollisionRegions(kinematics, collision, stairs, map, regions);
}

// BuildPipelineMap with kinematics made elsewhere: RunPipeline's attempts share one.
ConstrainedMap BuildMap(const RobotKinematics& kinematics, const Staircase& stairs, const PipelineOptions& options) {
  ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, options.facing, options.map);
  AddRobotRegions(kinematics, stairs, options, map);
  return map;
}

// The four-feet phases of `options.gait` (the crawl, the walk or the trot) on `stairs`.
double ShiftDuration(const PipelineOptions& options, const Staircase& stairs) {
  if (options.gait == GaitChoice::kWalk) return options.walk_shift_duration;
  if (options.gait == GaitChoice::kTrot) return options.trot_shift_duration;
  if (stairs.direction() == TravelDirection::kDown) return std::max(options.crawl.shift_duration, options.descent_shift_duration);
  return options.crawl.shift_duration;
}

// Why a gait's plan was not taken: its status reason, else its first violation.
std::string RejectionReason(const PipelineResult& result) {
  if (result.plan.status != PlanStatus::kOk) return result.plan.status_reason;
  if (result.validation.violations.empty()) return "not validated";
  const Violation& v = result.validation.violations.front();
  char text[200];
  std::snprintf(text, sizeof(text), "t=%.3f s, %s: %s, %.4g (%zu violation%s)", v.t, v.leg.c_str(), ToString(v.kind), v.value,
                result.validation.violations.size(), result.validation.violations.size() == 1 ? "" : "s");
  return text;
}

// One gait (the crawl, the walk or the trot) planned and validated; RunOnMap chooses among them.
PipelineResult RunGait(const RobotKinematics& kinematics, const Staircase& stairs, ConstrainedMap map,
                       PipelineOptions options) {
  const RobotModel& robot = kinematics.robot();
  options.crawl.shift_duration = ShiftDuration(options, stairs);
  options.crawl.diagonal_pairs = options.gait == GaitChoice::kTrot;
  PipelineResult result;
  result.map = std::move(map);
  result.clearances = ClearancesOf(options, stairs);
  // The alignment pose (seed 001 [0042]) and, when asked, the crawl's feet starting in its stance;
  // computed here only, for every footstep source.
  const AlignmentStance aligned = ComputeAlignmentStance(kinematics, stairs, result.map, options.facing,
                                                         options.crawl.body.hip_height_fraction, options.crawl.start_gap);
  result.approach = ApproachStairs(stairs, aligned, options.robot_pose, options.stair_mode, options.robot_pose_source);
  if (options.start_at_alignment && aligned.found) options.crawl.start_feet = aligned.feet;
  const auto t_plan = std::chrono::steady_clock::now();
  result.plan = FootstepPlan(kinematics, stairs, result.map, options);
  if (options.gait == GaitChoice::kWalk && result.plan.gait) result.plan.gait = Gait::kWalk;
  if (options.gait == GaitChoice::kTrot && result.plan.gait) result.plan.gait = Gait::kTrot;
  result.plan.timing_us = {{"plan", MicrosSince(t_plan)}};
  if (options.body == BodySource::kRecedingHorizonQp && result.plan.status == PlanStatus::kOk) {
    const std::vector<std::pair<std::string, double>> timing = result.plan.timing_us;
    // Where the robot stands is known when it starts at the alignment pose; else the body starts
    // over the feet.
    std::optional<Eigen::Vector2d> standing;
    if (options.start_at_alignment && aligned.found) standing = aligned.position.head<2>();
    result.plan = BodyOnFittedLayouts(kinematics, stairs, result.map, result.plan, options, standing);
    if (!options.body_nlp.empty() && result.plan.status == PlanStatus::kOk) {
      BodyNlpSettings nlp = options.nlp;
      nlp.solver = options.body_nlp;
      result.plan = RefineBodyNlp(robot, stairs, result.map, result.plan, options.body_qp, nlp);
    }
    result.plan.timing_us.insert(result.plan.timing_us.begin(), timing.begin(), timing.end());
  }
  if (options.validate && result.plan.status == PlanStatus::kOk) {
    const auto t_validate = std::chrono::steady_clock::now();
    TraversalValidator validator(kinematics, stairs, result.map, options.validation);
    result.validation = validator.Validate(result.plan);
    result.validated = true;
    result.plan.timing_us.emplace_back("validate", MicrosSince(t_validate));
  }
  return result;
}

// RunPipelineOnMap with the kinematics built once for the whole run: the map's robot regions and
// the alignment stance use the same ones. `options` come resolved by ForFootstepSource. Auto
// plans the trot, the walk where the validator rejects the trot's plan (or there is none), and
// the crawl where it rejects the walk's too.
PipelineResult RunOnMap(const RobotKinematics& kinematics, const Staircase& stairs, ConstrainedMap map,
                        PipelineOptions options) {
  RequireInRange("descent_shift_duration", options.descent_shift_duration, 0.0, 5.0);
  RequireInRange("walk_shift_duration", options.walk_shift_duration, 0.0, 5.0);
  RequireInRange("trot_swing_duration", options.trot_swing_duration, 0.05, 5.0);
  RequireInRange("trot_shift_duration", options.trot_shift_duration, 0.0, 5.0);
  RequireInRange("body_layouts", options.body_layouts, 0, 100);
  RequirePlannableGait(options.gait, options.footsteps);
  if (options.gait == GaitChoice::kAuto && !options.validate) options.gait = GaitChoice::kCrawl;
  if (options.gait != GaitChoice::kAuto) return RunGait(kinematics, stairs, std::move(map), options);
  // The fastest gait whose plan validates: the trot, the walk, else the crawl.
  std::vector<GaitRejection> rejected;
  std::vector<std::pair<std::string, double>> rejected_us;
  for (const auto& [choice, gait] : {std::pair{GaitChoice::kTrot, Gait::kTrot}, std::pair{GaitChoice::kWalk, Gait::kWalk}}) {
    const auto t_gait = std::chrono::steady_clock::now();
    options.gait = choice;
    PipelineResult result = RunGait(kinematics, stairs, map, options);
    const bool taken = result.plan.status == PlanStatus::kOk && result.validated && result.validation.ok;
    if (!taken) {
      rejected.push_back({gait, RejectionReason(result)});
      rejected_us.emplace_back(std::string(ToString(gait)) + "_rejected", MicrosSince(t_gait));
      continue;
    }
    result.plan.rejected_gaits = rejected;
    result.plan.timing_us.insert(result.plan.timing_us.begin(), rejected_us.begin(), rejected_us.end());
    return result;
  }
  options.gait = GaitChoice::kCrawl;
  PipelineResult crawl = RunGait(kinematics, stairs, std::move(map), options);
  crawl.plan.rejected_gaits = rejected;
  crawl.plan.timing_us.insert(crawl.plan.timing_us.begin(), rejected_us.begin(), rejected_us.end());
  return crawl;
}

}  // namespace

GaitChoice ParseGaitChoice(const std::string& text) {
  if (text == "crawl") return GaitChoice::kCrawl;
  if (text == "walk") return GaitChoice::kWalk;
  if (text == "trot") return GaitChoice::kTrot;
  if (text == "auto") return GaitChoice::kAuto;
  throw std::invalid_argument("gait: must be 'crawl', 'walk', 'trot' or 'auto' (got '" + text + "')");
}

void RequirePlannableGait(GaitChoice gait, FootstepSource footsteps) {
  if (gait != GaitChoice::kCrawl && footsteps != FootstepSource::kSelectedCrawl) {
    throw FieldError("gait", "the walk, the trot and auto plan the crawl's footholds, with --planner crawl only");
  }
}

FootstepSource ParseFootstepSource(const std::string& text) {
  if (text == "crawl") return FootstepSource::kSelectedCrawl;
  if (text == "step") return FootstepSource::kStepPlanner;
  if (text == "paper") return FootstepSource::kPaperCrawl;
  if (text == "paper-alt") return FootstepSource::kPaperCrawlAlternate;
  throw std::invalid_argument("planner: must be 'crawl', 'step', 'paper' or 'paper-alt' (got '" + text + "')");
}

bool IsPaperCrawl(FootstepSource source) {
  return source == FootstepSource::kPaperCrawl || source == FootstepSource::kPaperCrawlAlternate;
}

StepPlannerSettings CrawlControllers() {
  StepPlannerSettings settings;
  settings.gaits = {Gait::kCrawl, Gait::kCrawlAlternate};
  return settings;
}

PipelineOptions WithStairUncertainty(PipelineOptions options, const Staircase& stairs) {
  const double u = stairs.spec().uncertainty;
  if (u <= 0.0) return options;
  options.body_qp.clearance_margin += u;
  // Not the quasi-static path's touchdown clearance: its posture fit checks a few instants of
  // each swing for a height window, and 2.4 cm more left the footfall loop's descent none (a leg
  // out of reach, -50 mm on the stairs planned on); unraised, that plan keeps 12.3 mm on the true
  // stairs. The body optimisation owns the clearance of the posture it plans.
  options.crawl.swing.clearance += u;
  // Nor the step regions' margins off the edges and risers (5 and 7 cm, beyond any uncertainty
  // written): 2.4 cm more left the footfall loop's 5-step descent a crawl that tips (8.7 mm
  // outside the support) and grazes a nosing on the stairs planned on. Nor the robot regions'
  // clearance, judged at a nominal posture: raised with the others, two of the footfall loop's
  // four flights had no body-optimisation plan.
  return options;
}

PlannerClearances ClearancesOf(const PipelineOptions& options, const Staircase& stairs) {
  PlannerClearances c;
  c.stairs_uncertainty = stairs.spec().uncertainty;
  c.body_qp = options.body_qp.clearance_margin;
  c.touchdown = options.crawl.body.touchdown_clearance;
  c.swing = options.crawl.swing.clearance;
  c.edge_margin = options.map.edge_margin;
  c.riser_margin = options.map.riser_margin;
  c.validator = options.validation.min_clearance;
  return c;
}

void AddPipelineRobotRegions(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options,
                             ConstrainedMap& map) {
  if (!options.robot_regions) return;
  AddRobotRegions(RobotKinematics(robot), stairs, options, map);
}

ConstrainedMap BuildPipelineMap(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options) {
  return BuildMap(RobotKinematics(robot), stairs, options);
}

PipelineOptions OptionsForPlan(const Plan& plan) {
  PipelineOptions options;
  options.facing = plan.facing;
  if (std::isfinite(plan.hip_height_fraction)) options.crawl.body.hip_height_fraction = plan.hip_height_fraction;
  return options;
}

PipelineResult RunPipelineOnMap(const RobotModel& robot, const Staircase& stairs, ConstrainedMap map,
                                const PipelineOptions& given) {
  return RunOnMap(RobotKinematics(robot), stairs, std::move(map), WithStairUncertainty(ForFootstepSource(given), stairs));
}

PipelineResult RunPipeline(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& given) {
  const PipelineOptions options = WithStairUncertainty(ForFootstepSource(given), stairs);
  // The paper's crawl plans at the paper's posture whatever crawl.body says, and the body
  // optimisation finds its own: only the quasi-static path retries postures.
  const bool retry = !IsPaperCrawl(options.footsteps) && options.body == BodySource::kQuasiStaticPath;
  const std::size_t retries = retry ? options.posture_retries.size() : 0;
  const RobotKinematics kinematics(robot);
  PipelineResult first;
  bool near_miss = false;
  for (std::size_t attempt = 0; attempt <= retries; ++attempt) {
    PipelineOptions tried = options;
    if (attempt > 0) {
      const BodyPosture& posture = options.posture_retries[attempt - 1];
      if (posture.near_miss_only && !near_miss) continue;
      tried.crawl.body.hip_height_fraction = posture.hip_height_fraction;
      tried.crawl.body.pitch_fraction = posture.pitch_fraction;
      tried.crawl.keep_stance_length = options.crawl.keep_stance_length || posture.keep_stance_length;
      if (posture.height_key_period > 0.0) tried.crawl.body.height_key_period = posture.height_key_period;
      if (posture.stability_shift > 0.0) tried.crawl.body.stability_shift = posture.stability_shift;
      tried.crawl.body.check_swing_corners = options.crawl.body.check_swing_corners || posture.check_swing_corners;
      if (posture.refit_body_jumps) tried.crawl.refit_body_acceleration = options.validation.max_body_acceleration;
    }
    const auto t_map = std::chrono::steady_clock::now();
    ConstrainedMap map = BuildMap(kinematics, stairs, tried);
    const double map_us = MicrosSince(t_map);
    PipelineResult result = RunOnMap(kinematics, stairs, std::move(map), tried);
    result.plan.hip_height_fraction = tried.crawl.body.hip_height_fraction;
    result.plan.timing_us.insert(result.plan.timing_us.begin(), {"map", map_us});
    // Only a plan the validator rejected is worth another posture; the first attempt's answer
    // stands when none passes (its violations are the ones the default posture explains).
    const bool rejected = result.validated && !result.validation.ok && result.plan.status == PlanStatus::kOk;
    if (!rejected) return result;
    // The first attempt's near miss opens the near-miss postures, and so does a later one whose
    // body jumps while every leg reaches: the first attempt at (rise 0.218, run 0.208) also grazes
    // a nosing with the body, the tall pitched one (hip 0.8, pitch 1.0) jumps with a leg at its
    // limits, and the low body (hip 0.5) then validates. A taller posture that leaves a small
    // robot's legs short of reach is its size, not a near miss: A1 and Go2 on the default stairs
    // would plan 8 times instead of 3 (14 s instead of 5), none of them valid.
    near_miss = near_miss || (attempt == 0 ? IsNearMiss(result.validation) : IsJumpingNearMiss(result.validation));
    if (attempt == 0) first = std::move(result);
  }
  return first;
}

}  // namespace stairplan
