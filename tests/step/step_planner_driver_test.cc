// The offline driver on the default stairs (7 x 0.17 m rise, 0.27 m run, 0.02 m nosing), up and
// down, facing forward and backward, for the built-in robot and the five shared URDFs: every
// footstep lands in a step region (never in a collision region), within reach, and the leading and
// trailing legs keep their order ([0070]).
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/plan_json.h"
#include "stairplan/planning/step/step_planner_driver.h"
#include "step_test_util.h"
#include "test_paths.h"

using namespace stairplan;
using stairplan::testing::Extension;
using stairplan::testing::LiftoffAfter;

namespace {

void CheckPlan(const RobotModel& robot, TravelDirection direction, Facing facing) {
  StairSpec spec;
  spec.direction = direction;
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, facing);
  const StepPlannerSettings settings;
  const Plan plan = PlanWithStepPlanner(robot, stairs, map, settings);
  INFO(robot.name() << " " << ToString(direction) << " facing " << ToString(facing) << ": " << plan.status_reason);
  REQUIRE(plan.status == PlanStatus::kOk);
  REQUIRE(plan.footsteps.size() >= 4u * static_cast<std::size_t>(stairs.steps()) / 2u);
  REQUIRE(plan.selected >= 0);
  CHECK(plan.cadence_s == plan.controllers[static_cast<std::size_t>(plan.selected)].cadence_s);
  // Every foot ends on the last surface.
  std::map<std::string, int> last_stair;
  for (const Footstep& f : plan.footsteps) last_stair[f.leg] = f.stair_index;
  for (const auto& [leg, stair] : last_stair) CHECK(stair == map.size() - 1);
  for (const Footstep& f : plan.footsteps) {
    CAPTURE(f.leg, f.t_touchdown, f.position_W.x(), f.stair_index);
    REQUIRE(f.stair_index >= 0);
    CHECK(f.in_step_region);
    CHECK(map.InStepRegion(f.stair_index, f.position_W.head<2>()));
    CHECK_FALSE(map.InCollisionRegion(f.stair_index, f.position_W.head<2>()));
    CHECK(map.StairAt(f.position_W.head<2>()) == f.stair_index);
    CHECK(f.position_W.z() == Approx(map.stair(f.stair_index).z));
    const double e = Extension(robot, plan, f, f.t_touchdown);
    CHECK(e <= settings.reach_max_fraction + 1e-6);
    CHECK(e >= settings.reach_min_fraction - 1e-6);
    // Still in reach when the leg lifts the foot again (or at the end of the plan).
    const double lift = LiftoffAfter(plan, f);
    CHECK(Extension(robot, plan, f, lift) <= settings.reach_max_fraction + 1e-6);
  }
}

}  // namespace

TEST_CASE("driver: the built-in robot on the default stairs, all four ways", "[step]") {
  for (TravelDirection d : {TravelDirection::kUp, TravelDirection::kDown}) {
    for (Facing f : {Facing::kForward, Facing::kBackward}) CheckPlan(BuiltinRobot(), d, f);
  }
}

TEST_CASE("driver: the five shared robots on the default stairs, all four ways", "[step]") {
  const std::string dir = stairplan::testing::SharedPath("data/robots");
  if (dir.empty() || !std::filesystem::is_directory(dir)) {
    WARN("../shared/data/robots is absent: skipped");
    return;
  }
  int robots = 0;
  for (const char* name : {"unitree_a1", "unitree_go1", "unitree_go2", "anymal_b", "anymal_c"}) {
    const RobotModel robot = RobotModel::FromUrdfFile(dir + "/" + name + ".urdf");
    for (TravelDirection d : {TravelDirection::kUp, TravelDirection::kDown}) {
      for (Facing f : {Facing::kForward, Facing::kBackward}) CheckPlan(robot, d, f);
    }
    ++robots;
  }
  CHECK(robots == 5);
}

TEST_CASE("driver: leading and trailing legs ([0070])", "[step]") {
  for (TravelDirection d : {TravelDirection::kUp, TravelDirection::kDown}) {
    StairSpec spec;
    spec.direction = d;
    const Staircase stairs(spec);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
    REQUIRE(plan.status == PlanStatus::kOk);
    // The rear pair's leader is the right hind leg in every gait (the map faces forward, so travel
    // roles are body ones). When it lands, the left hind leg stands on the same stair or one behind
    // (below ascending, above descending: behind in travel order either way).
    std::map<std::string, int> stair = {{"LF", 0}, {"RF", 0}, {"LH", 0}, {"RH", 0}};
    int leads = 0, passes = 0, trailer_steps = 0;
    for (const Footstep& f : plan.footsteps) {
      stair[f.leg] = f.stair_index;
      CAPTURE(f.leg, f.t_touchdown);
      if (f.leg == "RH") {
        CHECK(stair["LH"] <= stair["RH"]);
        leads += stair["LH"] < stair["RH"] ? 1 : 0;
      }
      if (f.leg == "LH") {
        ++trailer_steps;
        passes += stair["LH"] > stair["RH"] ? 1 : 0;
      }
    }
    // The rule is exercised (the leader is at times a stair ahead), and the trailing leg passes its
    // leader only rarely (a soft rule, broken only when nothing else is in reach).
    CHECK(leads > 0);
    CHECK(passes * 10 <= trailer_steps);
  }
}

TEST_CASE("driver: plan.json carries the controllers and the selection", "[step]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
  const nlohmann::json j = PlanToJson(plan, stairs, map);
  REQUIRE(j["controllers"].size() == 15u);
  CHECK(j["selected"].get<int>() == plan.selected);
  const auto& chosen = j["controllers"][static_cast<std::size_t>(plan.selected)];
  CHECK(chosen["cadence_s"].get<double>() == Approx(j["cadence_s"].get<double>()));
  CHECK(chosen["gait"] == j["gait"]);
  CHECK(chosen["score"].is_number());
  CHECK(chosen["ruled_out_reason"].is_string());
  // The plan's controller is the one selected in the most cycles.
  for (const auto& c : j["controllers"]) CHECK(c["cycles_selected"].get<int>() <= chosen["cycles_selected"].get<int>());
  // Body samples are continuous in height (the pitch line, not the stairs' steps).
  for (std::size_t k = 1; k < plan.body.size(); ++k) CHECK(std::abs(plan.body[k].z - plan.body[k - 1].z) < 0.05);
}

TEST_CASE("driver: on shallow treads a leg passes over intermediate stairs ([0070])", "[step]") {
  StairSpec spec;
  spec.steps = 12;
  spec.rise = 0.08;
  spec.run = 0.13;
  spec.nosing = 0.0;
  const Staircase stairs(spec);
  ConstrainedMapSettings m;
  m.edge_margin = 0.02;
  m.riser_margin = 0.03;
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward, m);
  const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
  INFO(plan.status_reason);
  REQUIRE(plan.status == PlanStatus::kOk);
  int skips = 0;
  for (const Footstep& f : plan.footsteps) {
    CHECK(map.InStepRegion(f.stair_index, f.position_W.head<2>()));
    const int from = map.StairAt(f.from_W.head<2>());
    CHECK(f.stair_index >= from);  // never back down the flight
    skips += f.stair_index - from >= 2 ? 1 : 0;
  }
  CHECK(skips > 0);
}
