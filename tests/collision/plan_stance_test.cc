// Acceptance (issue 4): `stairplan plan --robot FILE` on the default stairs gives, at every
// touchdown, a stance whose four legs reach their footholds within joint limits and whose leg
// links are clear of the stairs. Checked for the built-in robot and the five shared robots on the
// plan the CLI makes (RunPipeline with the CLI's options: the step planner's cadence, robot-aware
// step regions, posture retries), from the plan's body pose and footholds, independently of the
// validator.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>
#include <utility>

#include "../kinematics/robot_files.h"
#include "leg_row_pipeline.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

struct Failure {
  int touchdowns = 0;
  int failed = 0;
  std::string first;
};

// The stance at one touchdown, described for a failure message.
std::string Describe(const StanceChecker& checker, const Footstep& step, const StanceResult& r) {
  std::ostringstream why;
  why << step.leg << " touchdown at t=" << step.t_touchdown << " s: " << ToString(r.status);
  for (int l = 0; l < 4; ++l) {
    const LegStance& s = r.legs[static_cast<std::size_t>(l)];
    why << "; " << checker.kinematics().leg(l).name() << " " << ToString(s.ik.status) << " err " << s.ik.error
        << " clearance " << s.stairs.distance << " (" << ToString(s.stairs.part) << ")";
  }
  return why.str();
}

// Checks every touchdown of `plan` on `stairs`; returns what failed.
Failure CheckTouchdowns(const RobotModel& robot, const Staircase& stairs, const Plan& plan) {
  StanceChecker checker(robot, stairs);
  Failure failure;
  std::map<std::string, Eigen::Vector3d> feet;
  for (std::size_t l = 0; l < plan.legs.size(); ++l) feet[plan.legs[l]] = plan.initial_feet_W[l];
  for (const Footstep& step : plan.footsteps) {
    feet[step.leg] = step.position_W;
    std::array<Eigen::Vector3d, 4> contacts;
    for (int l = 0; l < 4; ++l) contacts[static_cast<std::size_t>(l)] = feet[checker.kinematics().leg(l).name()];
    const StanceResult r = checker.Check(BodyPoseAt(plan.body, step.t_touchdown), contacts);
    ++failure.touchdowns;
    for (int l = 0; l < 4; ++l) {
      // Within limits is guaranteed by IK's contract; check it independently anyway.
      CHECK(checker.kinematics().leg(l).WithinLimits(r.legs[static_cast<std::size_t>(l)].ik.q));
    }
    if (r.ok()) continue;
    ++failure.failed;
    if (failure.first.empty()) failure.first = Describe(checker, step, r);
  }
  return failure;
}

// Plans the default stairs as `stairplan plan --body path --crawl-sequence pairs` does and checks
// its touchdowns (the posture fit's and the foothold search's work; the body optimisation's plans
// are judged by the validator alone); prints how far it got. Without `posture_retries` the first
// posture's plan: the pipeline's answer whenever no retry validates (RunPipeline keeps the first
// attempt's then).
void CheckCliPlan(const std::string& label, const RobotModel& robot, bool posture_retries = true) {
  const Staircase stairs{StairSpec{}};
  PipelineOptions cli = testing::PathBaselinePipeline();
  if (!posture_retries) cli.posture_retries.clear();
  const PipelineResult result = RunPipeline(robot, stairs, cli);
  REQUIRE(result.plan.status == PlanStatus::kOk);
  const Failure f = CheckTouchdowns(robot, stairs, result.plan);
  std::printf("plan stances %-12s %d/%d touchdowns ok (posture %.2f, validation %s, %zu violations)%s%s\n",
              label.c_str(), f.touchdowns - f.failed, f.touchdowns, result.plan.hip_height_fraction,
              result.validation.ok ? "ok" : "fails", result.validation.violations.size(),
              f.first.empty() ? "" : "; first failure: ", f.first.c_str());
  INFO(label << ": " << f.first);
  CHECK(f.touchdowns > 20);
  CHECK(f.failed == 0);
}

}  // namespace

TEST_CASE("the path baseline's stances are reachable and clear: built-in stairbot", "[plan_stance]") {
  CheckCliPlan("stairbot", BuiltinRobot());
}

TEST_CASE("the path baseline's stances are reachable and clear: shared robots", "[plan_stance]") {
  const auto robots = testing::TestRobots(false);
  if (robots.empty()) {
    WARN("shared robots skipped: ../shared not found");
    return;
  }
  // Under the sanitizers, where each robot's plan and check take minutes, the first robot only
  // (A1: its crawl needs the foothold search, the path worth running there), and its first
  // posture only: the validator rejects A1's plan in every posture, so the pipeline's answer is
  // that first plan anyway, and the seven retries were three quarters of the time (the descent
  // tests run them there).
  std::size_t checked = 0;
  for (const testing::RobotFile& file : robots) {
    if (checked == testing::FullOrSanitized<std::size_t>(robots.size(), 1)) break;
    CheckCliPlan(file.label, RobotModel::FromUrdfFile(file.path), !testing::kSanitized);
    ++checked;
  }
}

namespace {

// A shared robot's crawl with the pipeline's settings (`searched`) and with `change` applied to
// them (`changed`), both planned; found is false (and nothing planned) without ../shared.
struct CrawlPair {
  bool found = false;
  RobotModel robot;
  Plan changed, searched;
};

CrawlPair CrawlWithAndWithout(const std::string& label, const Staircase& stairs,
                              const std::function<void(CrawlSettings&)>& change) {
  CrawlPair pair;
  const auto robots = testing::TestRobots(false);
  const auto file = std::find_if(robots.begin(), robots.end(), [&](const testing::RobotFile& f) { return f.label == label; });
  if (file == robots.end()) return pair;
  pair.found = true;
  pair.robot = RobotModel::FromUrdfFile(file->path);
  const PipelineOptions options = testing::PathBaselinePipeline();  // the search is the pairs crawl's
  const ConstrainedMap map = BuildPipelineMap(pair.robot, stairs, options);
  CrawlSettings changed = options.crawl;
  change(changed);
  pair.changed = PlanCrawl(pair.robot, stairs, map, changed);
  pair.searched = PlanCrawl(pair.robot, stairs, map, options.crawl);
  REQUIRE(pair.changed.status == PlanStatus::kOk);
  REQUIRE(pair.searched.status == PlanStatus::kOk);
  return pair;
}

}  // namespace

// The crawl's foothold search (CrawlSettings::fit_footholds) is what gives the small robots
// standable touchdowns: without it, A1's front legs end beyond their knee limits.
TEST_CASE("without the crawl's foothold search A1's touchdowns fail, with it they pass", "[plan_stance]") {
  if (testing::kSanitized) return;
  const Staircase stairs{StairSpec{}};
  const CrawlPair plans = CrawlWithAndWithout("unitree_a1", stairs, [](CrawlSettings& s) { s.fit_footholds = 0; });
  if (!plans.found) return;
  const RobotModel& robot = plans.robot;
  const Plan& first = plans.changed;
  const Plan& searched = plans.searched;
  CHECK(CheckTouchdowns(robot, stairs, first).failed > 0);
  const Failure f = CheckTouchdowns(robot, stairs, searched);
  INFO(f.first);
  CHECK(f.failed == 0);
  // Every touchdown still lands inside its step region.
  for (const Footstep& step : searched.footsteps) CHECK(step.in_step_region);
}

namespace {

// The smallest circle any swing's three stance feet hold, seen from above [m].
double SmallestSupportInradius(const Plan& plan) {
  std::vector<Eigen::Vector3d> feet = plan.initial_feet_W;
  double smallest = 1e9;
  for (const Footstep& step : plan.footsteps) {
    const std::size_t swinging =
        static_cast<std::size_t>(std::find(plan.legs.begin(), plan.legs.end(), step.leg) - plan.legs.begin());
    std::vector<Eigen::Vector2d> stance;
    for (std::size_t i = 0; i < feet.size(); ++i) {
      if (i != swinging) stance.push_back(feet[i].head<2>());
    }
    const Eigen::Vector2d ab = stance[1] - stance[0], ac = stance[2] - stance[0];
    const double twice_area = std::abs(ab.x() * ac.y() - ab.y() * ac.x());
    smallest = std::min(smallest, twice_area / (ab.norm() + ac.norm() + (stance[2] - stance[1]).norm()));
    feet[swinging] = step.position_W;
  }
  return smallest;
}

}  // namespace

// On low stairs (rise 0.10 m, run 0.28 m) the short robots' hips are about one run apart, and the
// crawl moves its hind legs first: the lattice's first layout lands each hind foot on the spot
// its front foot still stands on (Go2 up, A1 down), and no body motion keeps the centre of mass
// over the line that leaves. The crawl's search takes another layout: the thin supports, the
// same side's legs in the stance checks and, where no layout passes every touchdown (A1), the
// rule that feet landing on feet are no plan all refuse that one.
TEST_CASE("no crawl swing stands on a support triangle too thin for the centre of mass", "[plan_stance]") {
  for (const auto& [label, direction] : {std::make_pair("unitree_go2", TravelDirection::kUp),
                                         std::make_pair("unitree_a1", TravelDirection::kDown)}) {
    // Under the sanitizers Go2's climb alone, of three steps (the whole test took two minutes
    // there): the same code.
    if (testing::kSanitized && std::string(label) != "unitree_go2") continue;
    StairSpec low;
    low.rise = 0.10;
    low.run = 0.28;
    low.steps = testing::FullOrSanitized(low.steps, 3);
    low.direction = direction;
    const CrawlPair plans = CrawlWithAndWithout(label, Staircase{low}, [](CrawlSettings& s) { s.fit_footholds = 0; });
    if (!plans.found) return;
    INFO(label);
    CHECK(SmallestSupportInradius(plans.changed) < 1e-3);
    CHECK(SmallestSupportInradius(plans.searched) >= CrawlSettings{}.min_support_inradius);
    for (const Footstep& step : plans.searched.footsteps) CHECK(step.in_step_region);
    // The lateral sequence (the default) lifts each front foot right after the hind foot behind it
    // lands beside it: no swing stands on both, and its lattice layout holds the circle unsearched.
    const ConstrainedMap map = BuildPipelineMap(plans.robot, Staircase{low}, PipelineOptions{});
    CrawlSettings lateral;
    lateral.fit_footholds = 0;
    const Plan unsearched = PlanCrawl(plans.robot, Staircase{low}, map, lateral);
    REQUIRE(unsearched.status == PlanStatus::kOk);
    CHECK(SmallestSupportInradius(unsearched) >= CrawlSettings{}.min_support_inradius);
  }
}

TEST_CASE("crawl settings name the bad field", "[plan_stance]") {
  CrawlSettings s;
  s.fit_footholds = -1;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("fit_footholds"));
  s = CrawlSettings{};
  s.trail_first_stride = 0.0;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("trail_first_stride"));
  s = CrawlSettings{};
  s.stance_treads = 11;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("stance_treads"));
  s = CrawlSettings{};
  s.min_support_inradius = -0.01;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("min_support_inradius"));
}
