// The walk (Gait::kWalk, PipelineOptions::gait): the crawl's footholds and swings with brief
// four-feet phases, judged by the validator's dynamic check; and auto, which takes the walk where
// its plan validates and the crawl where it does not.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "stairplan/geometry/field_error.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/validation/traversal_validator.h"
#include "gait_fixtures.h"

using namespace stairplan;

namespace {

PipelineResult PlanGait(const Staircase& stairs, GaitChoice gait) {
  PipelineOptions options;
  options.gait = gait;
  return RunPipeline(BuiltinRobot(), stairs, options);
}

// The four-feet phases: each gap between a touchdown and the next swing's liftoff.
std::vector<double> FourFeetPhases(const Plan& plan) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < plan.footsteps.size(); ++i) {
    gaps.push_back(plan.footsteps[i].t_liftoff - plan.footsteps[i - 1].t_touchdown);
  }
  return gaps;
}

void RequireValidated(const PipelineResult& result) {
  INFO(result.plan.status_reason);
  REQUIRE(result.plan.status == PlanStatus::kOk);
  REQUIRE(result.validated);
  INFO((result.validation.violations.empty() ? std::string() : ToString(result.validation.violations.front().kind)));
  REQUIRE(result.validation.ok);
}

bool IsDynamicKind(ViolationKind kind) { return FamilyOf(kind) == CheckFamily::kDynamics; }

}  // namespace

TEST_CASE("walk: the crawl's footholds with 0.2 s four-feet phases, a third faster up the default stairs, "
          "and its dynamic check judged and passed",
          "[pipeline][walk]") {
  const Staircase stairs = testing::DefaultStairs(TravelDirection::kUp);
  const PipelineResult crawl = PlanGait(stairs, GaitChoice::kCrawl);
  const PipelineResult walk = PlanGait(stairs, GaitChoice::kWalk);
  RequireValidated(crawl);
  RequireValidated(walk);
  REQUIRE(walk.plan.gait == Gait::kWalk);
  CHECK(crawl.plan.gait == Gait::kCrawl);
  // The same footholds in the same order: only the timing differs.
  REQUIRE(walk.plan.footsteps.size() == crawl.plan.footsteps.size());
  for (std::size_t i = 0; i < walk.plan.footsteps.size(); ++i) {
    CAPTURE(i);
    CHECK(walk.plan.footsteps[i].leg == crawl.plan.footsteps[i].leg);
    CHECK((walk.plan.footsteps[i].position_W - crawl.plan.footsteps[i].position_W).norm() < 1e-12);
  }
  const double shift = PipelineOptions{}.walk_shift_duration;
  for (const double gap : FourFeetPhases(walk.plan)) CHECK(gap == Approx(shift).margin(1e-9));
  for (const double gap : FourFeetPhases(crawl.plan)) CHECK(gap == Approx(CrawlSettings{}.shift_duration).margin(1e-9));
  // 35 four-feet phases 0.4 s shorter: 23.2 s against 37.2 s.
  CHECK(FlightDuration(walk.plan) < 0.65 * FlightDuration(crawl.plan));
  // The walk's verdict includes the dynamic check, and it found every wrench within the legs' reach;
  // the crawl's only reports it.
  CHECK(walk.validation.dynamics.mode == DynamicsCheckMode::kJudge);
  CHECK(walk.validation.dynamics.failed_instants == 0);
  CHECK(crawl.validation.dynamics.mode == DynamicsCheckMode::kReport);
  CHECK(walk.plan.rejected_gaits.empty());
}

TEST_CASE("auto: the fastest gait whose plan validates, the trot down the default stairs, the walk up them, the "
          "crawl up steep ones",
          "[pipeline][walk][trot]") {
  const PipelineResult down = PlanGait(testing::DefaultStairs(TravelDirection::kDown), GaitChoice::kAuto);
  RequireValidated(down);
  CHECK(down.plan.gait == Gait::kTrot);
  CHECK(down.plan.rejected_gaits.empty());

  const PipelineResult up = PlanGait(testing::DefaultStairs(TravelDirection::kUp), GaitChoice::kAuto);
  RequireValidated(up);
  CHECK(up.plan.gait == Gait::kWalk);
  REQUIRE(up.plan.rejected_gaits.size() == 1);
  CHECK(up.plan.rejected_gaits[0].gait == Gait::kTrot);

  // Up steep stairs (rise 0.20 m, run 0.30 m) the trot and the walk ask for wrenches the legs
  // cannot produce: every violation of the walk's plan is the dynamic check's, which the crawl only
  // reports, and auto says so for both.
  StairSpec steep_spec;
  steep_spec.rise = 0.20;
  steep_spec.run = 0.30;
  const Staircase steep(steep_spec);
  const PipelineResult walk = PlanGait(steep, GaitChoice::kWalk);
  REQUIRE(walk.plan.status == PlanStatus::kOk);
  REQUIRE_FALSE(walk.validation.ok);
  for (const Violation& v : walk.validation.violations) {
    CAPTURE(v.t, v.leg, ToString(v.kind));
    CHECK(IsDynamicKind(v.kind));
  }
  const PipelineResult crawl = PlanGait(steep, GaitChoice::kAuto);
  RequireValidated(crawl);
  CHECK(crawl.plan.gait == Gait::kCrawl);
  REQUIRE(crawl.plan.rejected_gaits.size() == 2);
  CHECK(crawl.plan.rejected_gaits[0].gait == Gait::kTrot);
  CHECK(crawl.plan.rejected_gaits[1].gait == Gait::kWalk);
  const Violation& first = walk.validation.violations.front();
  CHECK_THAT(crawl.plan.rejected_gaits[1].reason, Catch::Contains(ToString(first.kind)) && Catch::Contains(first.leg));
  const auto& timing = crawl.plan.timing_us;
  for (const char* stage : {"trot_rejected", "walk_rejected"}) {
    CAPTURE(stage);
    CHECK(std::any_of(timing.begin(), timing.end(), [stage](const auto& s) { return s.first == stage; }));
  }
}

TEST_CASE("walk: the validator judges a walk's dynamics and only reports a crawl's, off staying off",
          "[pipeline][walk][validation]") {
  const Staircase stairs = testing::DefaultStairs(TravelDirection::kDown);
  const PipelineResult walk = PlanGait(stairs, GaitChoice::kWalk);
  REQUIRE(walk.plan.status == PlanStatus::kOk);
  const RobotModel robot = BuiltinRobot();
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, PipelineOptions{});
  Plan plan = walk.plan;
  TraversalValidator validator(robot, stairs, map);
  const ValidationReport judged = validator.Validate(plan);
  CHECK_FALSE(judged.ok);
  CHECK(judged.dynamics.failed_instants > 0);
  // The same body and footsteps labelled a crawl: the same dynamic findings, no longer a verdict.
  plan.gait = Gait::kCrawl;
  const ValidationReport reported = validator.Validate(plan);
  CHECK(reported.ok);
  CHECK(reported.dynamics.mode == DynamicsCheckMode::kReport);
  CHECK(reported.dynamics.failed_instants == judged.dynamics.failed_instants);
  // Switched off, the dynamic check judges no gait.
  plan.gait = Gait::kWalk;
  ValidationSettings off;
  off.dynamics.mode = DynamicsCheckMode::kOff;
  TraversalValidator unchecked(robot, stairs, map, off);
  CHECK(unchecked.Validate(plan).ok);
}

TEST_CASE("walk: on stairs with a friction coefficient of 0.2 the walk up fails the dynamic check, the instant and "
          "the leg named",
          "[pipeline][walk][validation]") {
  const Staircase stairs = testing::DefaultStairs(TravelDirection::kUp);
  const PipelineResult walk = PlanGait(stairs, GaitChoice::kWalk);
  RequireValidated(walk);
  const ValidationReport report = testing::ValidateOnFriction(walk.plan, stairs, 0.2);
  REQUIRE_FALSE(report.ok);
  const Violation& first = report.violations.front();
  CAPTURE(first.t, first.leg, ToString(first.kind), first.value);
  CHECK(IsDynamicKind(first.kind));
  CHECK(first.leg_id != LegId::kNone);
  CHECK(first.t > 0.0);
  CHECK(first.t < walk.plan.duration());
  CHECK(report.dynamics.first_failure_t == Approx(first.t));
}

TEST_CASE("walk: the walk and auto refuse other footstep planners and a bad shift duration, naming the field",
          "[pipeline][walk]") {
  const Staircase stairs = testing::DefaultStairs(TravelDirection::kUp);
  PipelineOptions options;
  options.gait = GaitChoice::kWalk;
  options.footsteps = FootstepSource::kStepPlanner;
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), stairs, options), Catch::Contains("gait"));
  options.footsteps = FootstepSource::kSelectedCrawl;
  options.walk_shift_duration = -0.1;
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), stairs, options), Catch::Contains("walk_shift_duration"));
  CHECK(ParseGaitChoice("auto") == GaitChoice::kAuto);
  CHECK_THROWS_WITH(ParseGaitChoice("gallop"), Catch::Contains("gait") && Catch::Contains("gallop"));
}
