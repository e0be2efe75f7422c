// The body optimisation judges the crawl's foothold layouts and swing orders
// (PipelineOptions::body_layouts): where it finds no body on the crawl's own footholds, it plans on
// the crawl's other layouts fitted to the robot, then on all of them in the other lateral order,
// and keeps the first on which it finds one.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/crawl_planner.h"
#include "leg_names.h"
#include "sanitized.h"
#include "shared_robot.h"

using namespace stairplan;

namespace {

// The most stairs a front foot ever stands above the hind foot on its side, at a touchdown.
int FrontTreadsAhead(const Plan& plan) {
  std::map<std::string, int> stair;  // each foot's stair; the start is on the landing, stair 0
  for (const std::string& leg : plan.legs) stair[leg] = 0;
  int most = 0;
  for (const Footstep& step : plan.footsteps) {
    stair[step.leg] = step.stair_index;
    most = std::max({most, stair["LF"] - stair["LH"], stair["RF"] - stair["RH"]});
  }
  return most;
}

// The body planned on the crawl's own footholds only (not validated), and with the layout search.
struct OwnAndSearched {
  PipelineResult own, searched;
};

OwnAndSearched PlanBothWays(const RobotModel& robot, const Staircase& stairs, Facing facing = Facing::kForward) {
  PipelineOptions searched;
  searched.facing = facing;
  PipelineOptions own = searched;
  own.body_layouts = 0;
  own.validate = false;
  return {RunPipeline(robot, stairs, own), RunPipeline(robot, stairs, searched)};
}

// The plan on the crawl's own footholds found no body, the reason containing `binding`.
void RequireOwnFails(const PipelineResult& own, const std::string& binding) {
  INFO("the crawl's footholds: " << own.plan.status_reason);
  REQUIRE(own.plan.status == PlanStatus::kInfeasible);
  CHECK_THAT(own.plan.status_reason, Catch::Contains(binding));
}

// The searched plan found a body, and it validates with the validator's clearance to spare.
void RequireValid(const PipelineResult& searched) {
  INFO("searched: " << searched.plan.status_reason);
  REQUIRE(searched.plan.status == PlanStatus::kOk);
  REQUIRE(searched.validated);
  CHECK(searched.validation.ok);
  CHECK(searched.validation.min_clearance_m >= searched.clearances.validator);
}

// The layout search rescuing shared robot `name` on `spec`: on the crawl's own footholds the body
// optimisation finds no body, the reason containing `binding`, and the searched plan validates.
// None where ../shared is absent.
std::optional<OwnAndSearched> RequireSearchRescues(const std::string& name, const StairSpec& spec, Facing facing,
                                                   const std::string& binding) {
  const std::optional<RobotModel> robot = testing::SharedRobot(name);
  if (!robot) return std::nullopt;
  OwnAndSearched plans = PlanBothWays(*robot, Staircase(spec), facing);
  RequireOwnFails(plans.own, binding);
  RequireValid(plans.searched);
  return plans;
}

}  // namespace

TEST_CASE("the body optimisation takes Unitree Go2 up the default stairs on footholds it chose among the crawl's layouts",
          "[planning][layouts]") {
  // On the crawl's own footholds its front feet stand two treads above its hind feet, far ahead of
  // their hips, and the front shanks lie on the nosings behind them: no body the optimisation
  // plans lifts them (the shank pivots about its foot, and the clearance's gradient in the body's
  // motion is below 0.1). One tread apart, it climbs. The normal build only (two minutes under the
  // sanitizers): there "a body the optimisation finds on no layout" runs the same search.
  // The searched plan's validation checks the body at t = 0 too: on the layout found the robot
  // starts nearer the flight, and at its nominal height its head would overhang the first nosing by
  // 15 mm.
  if (testing::kSanitized) return;
  const std::optional<OwnAndSearched> plans =
      RequireSearchRescues("unitree_go2", StairSpec{}, Facing::kForward, "RF: clearance below the margin");
  if (!plans) return;
  CHECK(FrontTreadsAhead(plans->own.plan) == 2);
  CHECK(FrontTreadsAhead(plans->searched.plan) == 1);
}

TEST_CASE("the re-check that judges a layout checks swing legs and leg pairs: Unitree Go2 descends the low stairs",
          "[planning][layouts]") {
  // On the crawl's own footholds the body optimisation plans a descent whose right hind leg,
  // swinging, passes through its standing front leg (-39 mm at 6.16 s). A re-check of the stance
  // legs alone passed it; with the swing legs and the pairs of neighbouring legs it is turned
  // down, and a later layout keeps them apart. The normal build only (on four steps or fewer the
  // crawl's footholds plan clear; five take 2 min under the sanitizers): there "the body re-check
  // passes the nominal stance and names the legs of a crossed pair" checks the pairs.
  if (testing::kSanitized) return;
  StairSpec spec;
  spec.rise = 0.10;
  spec.run = 0.28;
  spec.direction = TravelDirection::kDown;
  RequireSearchRescues("unitree_go2", spec, Facing::kForward, "RF/RH: legs closer than the margin");
}

TEST_CASE("a body the optimisation finds on no layout: the first layout's reason, and how many others failed",
          "[planning][layouts]") {
  // Unitree A1 facing forward up the default stairs. Its crawl's own layout lands each hind foot on
  // its front foot's foothold before that foot lifts: no body makes that valid (planned on it, the
  // body optimisation finds the right legs closer than the margin at the first swing), so the
  // search plans none there and says so, then why the next layout failed; one other suffices to
  // show the report. The verdict is the rise's: on 0.10 m steps (run 0.28 m) the same robot
  // climbs, and the plan validates. Under the sanitizers the report on two steps only.
  const std::optional<RobotModel> a1 = testing::SharedRobot("unitree_a1");
  if (!a1) return;
  StairSpec spec;
  spec.steps = testing::FullOrSanitized(7, 2);
  PipelineOptions options;
  options.validate = false;
  options.body_layouts = 1;
  PipelineOptions own = options;
  own.body_layouts = 0;
  const PipelineResult on_own = RunPipeline(*a1, Staircase(spec), own);
  const TouchdownCrowding crowding = CrowdedTouchdowns(*a1, on_own.plan);
  CHECK(crowding.touchdowns > 0);
  CHECK(crowding.leg == "RH");
  CHECK(crowding.onto == "RF");
  const PipelineResult r = RunPipeline(*a1, Staircase(spec), options);
  INFO(r.plan.status_reason);
  REQUIRE(r.plan.status == PlanStatus::kInfeasible);
  const std::string crowded = "footholds: " + std::to_string(crowding.touchdowns) + " touchdowns on a foot that still stands";
  CHECK_THAT(r.plan.status_reason, Catch::StartsWith(crowded + " (the first at t="));
  CHECK_THAT(r.plan.status_reason, Catch::Contains("; on the next layout, body re-check: t="));
  CHECK_THAT(r.plan.status_reason, Catch::EndsWith("; none on 1 other foothold layout or order either"));
  if (testing::kSanitized) return;
  RequireOwnFails(on_own, "RF/RH: legs closer than the margin");

  spec.rise = 0.10;
  spec.run = 0.28;
  options.validate = true;
  options.body_layouts = PipelineOptions{}.body_layouts;
  const PipelineResult low = RunPipeline(*a1, Staircase(spec), options);
  INFO("low stairs: " << low.plan.status_reason);
  REQUIRE(low.plan.status == PlanStatus::kOk);
  REQUIRE(low.validated);
  CHECK(low.validation.ok);
}

TEST_CASE("Unitree Go2 facing backward: no layout in either order keeps its legs the execution margin off the default stairs, the low ones do",
          "[planning][layouts][progress]") {
  // Walking backward up the default stairs, on every layout and in both swing orders the body
  // re-check finds a leg's links nearer the stairs than the body QP's 5 mm execution margin, or
  // the body stepping back to keep it; the crawl's own footholds fail on the margin first, and the
  // reason says so. Without that margin the climb validates. On 0.10 m steps (run 0.28 m) the
  // same robot climbs backward, and the plan validates. The normal build only (two dozen
  // candidates; "the body re-check refuses a body that moves back along the travel beyond the
  // bound" checks the retreat's refusal under the sanitizers).
  if (testing::kSanitized) return;
  const std::optional<RobotModel> go2 = testing::SharedRobot("unitree_go2");
  if (!go2) return;
  PipelineOptions options;
  options.facing = Facing::kBackward;
  StairSpec spec;
  const PipelineResult steep = RunPipeline(*go2, Staircase(spec), options);
  INFO(steep.plan.status_reason);
  REQUIRE(steep.plan.status == PlanStatus::kInfeasible);
  CHECK_THAT(steep.plan.status_reason, Catch::Contains("clearance below the margin"));
  CHECK_THAT(steep.plan.status_reason, Catch::Contains("other foothold layouts or orders either"));
  // The margin is the binding constraint: without it the climb validates.
  PipelineOptions no_margin = options;
  no_margin.body_qp.clearance_margin = 0.0;
  const PipelineResult unmargined = RunPipeline(*go2, Staircase(spec), no_margin);
  INFO("no margin: " << unmargined.plan.status_reason);
  REQUIRE(unmargined.plan.status == PlanStatus::kOk);
  REQUIRE(unmargined.validated);
  CHECK(unmargined.validation.ok);
  spec.rise = 0.10;
  spec.run = 0.28;
  const PipelineResult low = RunPipeline(*go2, Staircase(spec), options);
  RequireValid(low);
}

TEST_CASE("the other lateral order carries Unitree A1 backward up the low stairs, where the crawl's order finds no body",
          "[planning][layouts]") {
  // Climbing backward, A1's trailing front legs swing first in the lateral-sequence crawl, toward
  // hind legs that still stand, and its right legs come closer than the margin at the first swing.
  // With each leading leg first the stance stretches where it shortened, and the climb validates.
  // The normal build only (under the sanitizers "a body the optimisation finds on no layout"
  // runs the same search).
  if (testing::kSanitized) return;
  StairSpec spec;
  spec.rise = 0.10;
  spec.run = 0.28;
  const std::optional<OwnAndSearched> plans =
      RequireSearchRescues("unitree_a1", spec, Facing::kBackward, "RF/RH: legs closer than the margin");
  if (!plans) return;
  // The first swing is a leading leg's: its foot stands ahead of its neighbour's along the travel.
  const Plan& plan = plans->searched.plan;
  REQUIRE(!plan.footsteps.empty());
  const std::string first = plan.footsteps.front().leg;
  const std::string neighbour = testing::SameSideLeg(first);
  double neighbour_x = 0.0;
  for (std::size_t l = 0; l < plan.legs.size(); ++l) {
    if (plan.legs[l] == neighbour) neighbour_x = plan.initial_feet_W[l].x();
  }
  CHECK(plan.footsteps.front().from_W.x() > neighbour_x);
}

TEST_CASE("body_layouts out of range is refused, naming the field", "[planning][layouts]") {
  PipelineOptions options;
  options.body_layouts = -1;
  StairSpec spec;
  spec.steps = 1;
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), Staircase(spec), options), Catch::Contains("body_layouts"));
}
