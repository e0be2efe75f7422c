// The whole planning pipeline for one staircase, in one place so that the CLI, sweeps and tests
// run the same thing: constrained map -> footsteps -> body -> (validation), with stage timings.
#pragma once

#include <optional>

#include "stairplan/collision/robot_collision_regions.h"
#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/crawl_planner.h"
#include "stairplan/body_nlp/body_nlp.h"
#include "stairplan/planning/body/body_planner_settings.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/planner_clearances.h"
#include "stairplan/planning/stair_approach.h"
#include "stairplan/planning/step/step_planner_settings.h"
#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan {

/// Where the footsteps come from.
enum class FootstepSource {
  /// The step planner selects the controller (cadence); the crawl puts every foot at the centre of
  /// a step region at that cadence, with four-feet phases for the COM shifts. Validates today.
  kSelectedCrawl,
  /// The step planner's own footsteps, retimed with four-feet phases, under the quasi-static body
  /// path. Its plans do not all validate yet (shank clearances at nosings).
  kStepPlanner,
  /// The 2012 paper's crawl, case 1 (stairplan/planning/step/paper_crawl.h): its own footholds, timing,
  /// posture (PaperCrawlSettings::body, which the map and the alignment stance are made for) and
  /// quasi-static body path; climbing facing forward only. Its posture is the paper's, so no
  /// posture is retried, and it has no receding-horizon body.
  kPaperCrawl,
  /// The paper's crawl, case 2: the front feet's contact offsets switched.
  kPaperCrawlAlternate,
};
/// Where the body trajectory comes from.
enum class BodySource {
  /// The quasi-static path: COM over the stance triangle while a leg swings, fitted by a posture
  /// search and the posture retries (a baseline to compare with; the paper's crawl's own body).
  kQuasiStaticPath,
  /// The receding-horizon body optimisation run forward over the flight, one cycle per knot, as a
  /// control loop would run it (stairplan/planning/body/plan_body.h), with body_qp's rows; optionally
  /// refined by the NLP. The default.
  kRecedingHorizonQp,
};

/// Which gait the pipeline plans on the crawl's footholds.
enum class GaitChoice {
  /// The crawl (Gait::kCrawl): four-feet phases of crawl.shift_duration between the swings
  /// (descent_shift_duration going down), its balance judged by the support polygon.
  kCrawl,
  /// The walk (Gait::kWalk): the same footholds and swings with four-feet phases of
  /// walk_shift_duration, climbing and descending; the validator's dynamic check judges it.
  kWalk,
  /// The trot (Gait::kTrot): the same footholds, the diagonal pairs swinging together for
  /// trot_swing_duration with trot_shift_duration of four feet down between them; the body
  /// balances its pendulum's ZMP on the standing diagonal and the dynamic check judges it.
  kTrot,
  /// The fastest gait whose plan validates: the trot, else the walk, else the crawl
  /// (Plan::rejected_gaits says why not the faster ones). Without validation
  /// (PipelineOptions::validate off) nothing can judge the faster gaits: the crawl.
  kAuto,
};

/// "crawl", "walk", "trot" or "auto"; throws std::invalid_argument otherwise.
GaitChoice ParseGaitChoice(const std::string& text);

/// Throws FieldError("gait") unless `footsteps` can plan `gait`: the walk, the trot and auto plan the
/// crawl's footholds (FootstepSource::kSelectedCrawl) only.
void RequirePlannableGait(GaitChoice gait, FootstepSource footsteps);

/// "crawl", "step", "paper" or "paper-alt"; throws std::invalid_argument otherwise.
FootstepSource ParseFootstepSource(const std::string& text);

/// True for the 2012 paper's crawl, either case: it plans its own posture and body path.
bool IsPaperCrawl(FootstepSource source);

/// Step planner settings with the crawl gaits only.
StepPlannerSettings CrawlControllers();

/// A stance posture for the quasi-static body path (see BodyPathSettings), the crawl's
/// footholds under it (CrawlSettings::keep_stance_length), how often the posture fit checks
/// a swing (BodyPathSettings::height_key_period; 0: crawl.body's) and how far the COM leans
/// over the support triangle while a leg swings (BodyPathSettings::stability_shift; 0:
/// crawl.body's).
struct BodyPosture {
  double hip_height_fraction = 0.6;  ///< BodyPathSettings::hip_height_fraction
  double pitch_fraction = 0.75;  ///< BodyPathSettings::pitch_fraction
  bool keep_stance_length = false;  ///< CrawlSettings::keep_stance_length
  double height_key_period = 0.0;  ///< BodyPathSettings::height_key_period (0: crawl.body's)
  /// Tried only after a near miss: the first attempt rejected for body jumps, legs at their reach
  /// or limits or on the stairs alone (or a later one that also jumps, every leg reaching), what
  /// the postures for steep steps address. They do
  /// nothing for a plan that tips or puts the body on the stairs, and a robot whose plans fail
  /// that way everywhere would pay for each of them.
  bool near_miss_only = false;
  double stability_shift = 0.0;  ///< BodyPathSettings::stability_shift (0: crawl.body's)
  bool check_swing_corners = false;  ///< BodyPathSettings::check_swing_corners
  /// The crawl's foothold search also runs for a body that jumps beyond the validator's bound
  /// (CrawlSettings::refit_body_acceleration).
  bool refit_body_jumps = false;
};

/// What RunPipeline() plans with: the planners chosen and every stage's settings.
struct PipelineOptions {
  Facing facing = Facing::kForward;  ///< which way the body faces relative to the travel
  FootstepSource footsteps = FootstepSource::kSelectedCrawl;  ///< which planner places the footsteps
  /// The gait; the walk, the trot and auto plan the crawl's footholds (FootstepSource::kSelectedCrawl) only.
  GaitChoice gait = GaitChoice::kCrawl;
  /// The walk's four-feet phases between swings, up and down [s]: a third of the crawl's, short
  /// enough to cut the flight by about 40 %; where the legs cannot produce the quicker shifts'
  /// wrench, the dynamic check rejects the walk (and auto plans the crawl).
  double walk_shift_duration = 0.2;
  ///@{
  /// The trot's swings of a diagonal pair, and its four-feet phases between them [s]: the default
  /// seven steps' 18 pair swings take under 8 s from the first liftoff to the last touchdown.
  double trot_swing_duration = 0.25;
  double trot_shift_duration = 0.15;
  ///@}
  /// The step planner's controllers; the executed gait is quasi-static, so crawls only by default.
  StepPlannerSettings step = CrawlControllers();
  /// Which planner makes the body trajectory; the paper's crawl always plans its own path.
  BodySource body = BodySource::kRecedingHorizonQp;
  BodyPlannerSettings body_qp = LegRowBodySettings();  ///< for kRecedingHorizonQp (knots = the horizon)
  /// Where the body optimisation finds no body on the crawl's footholds, it plans on up to this
  /// many other footholds and keeps the first on which it finds one: the crawl's other layouts
  /// fitted to the robot (FittedLayouts()), then its own and those in the other lateral order
  /// (OtherLateralOrder()). Unitree Go2 climbs the default stairs with its front
  /// feet one tread ahead of its hind ones, not two (there its front shanks, reaching far ahead
  /// of the hips, lie on the nosings behind the feet). Each that fails, the crawl's own too, is
  /// planned only to its first failure, which the reason names. 0: the crawl's footholds only,
  /// planned in full (the reason names the first failure of each kind).
  int body_layouts = 48;
  std::string body_nlp;          ///< "", "ipopt" or "nlopt": refine the QP body with the NLP
  BodyNlpSettings nlp;  ///< the NLP's solver settings, with body_nlp
  ConstrainedMapSettings map;  ///< the analytic map's margins
  /// Trim step regions where this robot's legs would hit a riser or nosing (collision module).
  bool robot_regions = true;
  RobotRegionSettings regions;  ///< how the robot's own collision regions are found
  CrawlSettings crawl;  ///< the crawl planner's settings (and its body path's, crawl.body)
  /// Going down, the crawl's four-feet phases last at least this long [s] (0: crawl.shift_duration
  /// as it is). The COM rides high above the lower front feet (0.57 m for the built-in robot on
  /// the default stairs), so the deceleration that ends a 0.6 s shift (about 2 m/s^2) pushes the
  /// ZMP over the front and downhill side feet: the hind stance foot unloads and slides (18 cm in
  /// MuJoCo at the plan's pace). At 0.8 s the feet hold (2.5 cm, rolling and creep).
  double descent_shift_duration = 0.8;
  bool validate = true;  ///< replay the plan through the validator
  /// Postures RunPipeline tries, in order, after crawl.body's when the validator rejects a plan:
  /// descending, the legs need to stand taller and the body to pitch with the whole flight to
  /// keep the shanks off the nosings behind the feet (the built-in robot's default descents pass
  /// with the second and third). Climbing steep stairs (rise + run about 0.425 m for the built-in
  /// robot), the posture fit finds no height that suits a whole swing and the body would jump:
  /// trailing feet one stance length behind the leading ones, or a lower body, let it ride
  /// smoothly. On long steep steps the legs work at their limits and the fit's windows narrow:
  /// checked every 0.1 s, a leg passes its limit between the instants checked; every 0.05 s
  /// (twice the fit's work) it does not. On the steepest long steps (rise 0.23-0.25 m, run
  /// 0.31-0.35 m) a swing foot lifted straight up from its tread comes so near its hip that the
  /// hip's abduction runs into its limit at the top of the lift when the body leans sideways over
  /// the support triangle (the swing leg's hip moves away from its foot): leaning 60 % of the way
  /// keeps it in range (COM margins 12-47 mm on the sweep's steep corner, 10 required), with the
  /// fit checking the top of each lift (a 0.25 s swing's checks every 0.1 s miss it) and, where
  /// the front feet still reach too far for any posture and the body would jump, the crawl's
  /// foothold search (rise 0.25, runs 0.342 and 0.35). Empty: one attempt.
  /// keep_stance_length applies to the quasi-static path only.
  std::vector<BodyPosture> posture_retries = {{0.8, 1.0},
                                              {0.8, 0.75},
                                              {0.6, 0.75, true, 0.0, true},
                                              {0.5, 0.75, false, 0.0, true},
                                              {0.8, 0.75, false, 0.05, true},
                                              {0.6, 0.75, false, 0.05, true},
                                              {0.6, 0.75, false, 0.0, true, 0.6, true, true}};
  ValidationSettings validation;  ///< what the validator checks and with what margins
  /// The robot's tracked pose in the plan's frame: stair mode is judged there (stairplan/planning/stair_approach.h).
  /// None: the robot is taken to be at the alignment pose.
  std::optional<GroundPose> robot_pose;
  /// Where robot_pose came from, as the result's approach (and plan.json) reports it.
  RobotPoseSource robot_pose_source = RobotPoseSource::kGiven;
  StairModeSettings stair_mode;  ///< when stair mode engages
  /// Start the crawl's feet in the alignment stance, so that the plan's first state is the
  /// alignment pose (stairplan/planning/stair_alignment.h). Off by default: from the standing stance the
  /// crawl's first strides reach up to one and a half runs, and some flights' plans no longer
  /// validate (stairbot climbing rise 0.22-0.25 m on runs of 0.20 and 0.35 m, the Unitree A1 on
  /// rise 0.10 m, run 0.28 m). Off, the feet start on the footholds nearest under the hips and
  /// PlanStartOffset() says how far the plan's first state is from the alignment pose. The
  /// paper's crawl keeps its own start either way.
  bool start_at_alignment = false;
};


/// `options` with the planners' clearance margins raised by `stairs.spec().uncertainty`: the body
/// optimisation's (body_qp.clearance_margin, which its clearance rows keep for stance and swing
/// legs) and the swings' (SwingSettings::clearance over the nosings). Stairs estimated from data
/// are off by up to that much at their nosings, and a clearance is 1-Lipschitz in where the stairs
/// are, so a plan that keeps its margin plus the uncertainty on the estimate keeps its margin on
/// the true stairs. The quasi-static path's touchdown clearance, the step regions' margins and the
/// robot regions' clearance are not raised (stairplan/pipeline/plan_pipeline.cc says why); the validator's
/// margins are a judge's, on the stairs it is given. RunPipeline and RunPipelineOnMap call it:
/// give them the options as set (the map builders read none of the margins it raises).
PipelineOptions WithStairUncertainty(PipelineOptions options, const Staircase& stairs);

/// The clearances `options` keep (after WithStairUncertainty) on `stairs`.
PlannerClearances ClearancesOf(const PipelineOptions& options, const Staircase& stairs);

/// What RunPipeline() produced: the map planned on, the plan and its validation.
struct PipelineResult {
  ConstrainedMap map;  ///< the constrained map planned on
  Plan plan;  ///< the plan
  bool validated = false;  ///< the validator ran
  ValidationReport validation;  ///< meaningful when validated
  StairApproach approach;  ///< the alignment pose (the start with start_at_alignment), and stair mode at the robot's pose
  PlannerClearances clearances;  ///< the clearances the planners kept (their margins plus the stairs' uncertainty)
};

/// The constrained map the pipeline plans on: analytic margins plus, when asked, the robot's own
/// collision regions.
ConstrainedMap BuildPipelineMap(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options);

/// The pipeline's options for judging a finished plan: its facing and the posture it was planned
/// for (Plan::hip_height_fraction), so the map rebuilt from them is the one it was planned on.
PipelineOptions OptionsForPlan(const Plan& plan);

/// Adds the robot's own collision regions to `map` when the options ask for them.
void AddPipelineRobotRegions(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options,
                             ConstrainedMap& map);

/// Plans `stairs` for `robot` on a map made elsewhere (perception); the rest as RunPipeline.
PipelineResult RunPipelineOnMap(const RobotModel& robot, const Staircase& stairs, ConstrainedMap map,
                                const PipelineOptions& options = {});

/// Plans `stairs` for `robot`. Throws std::invalid_argument only for invalid options; a staircase
/// the robot cannot traverse gives a plan with status kInfeasible.
PipelineResult RunPipeline(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options = {});

}  // namespace stairplan
