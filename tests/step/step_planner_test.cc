// The per-cycle step planner: selection against the constrained map (seed 000 [0034]-[0035]), hard
// rule-outs with reasons, deterministic tie-breaks and hysteresis, targets inside step regions.
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/step_planner.h"
#include "stairplan/planning/step/step_planner_driver.h"
#include "step_test_util.h"

using namespace stairplan;

namespace {

constexpr double kCadence = 0.35;  // the cadence the constructed map is made for

// Low, shallow steps whose step regions are the whole treads (no margins).
ConstrainedMap OpenMap(const Staircase& stairs) {
  ConstrainedMapSettings m;
  m.edge_margin = 0.0;
  m.riser_margin = 0.0;
  m.side_margin = 0.05;
  m.min_region_depth = 0.0;
  return ConstrainedMap::FromStaircase(stairs, Facing::kForward, m);
}

Staircase SteppingStones() {
  StairSpec spec;
  spec.steps = 40;
  spec.rise = 0.02;
  spec.run = 0.24;
  spec.nosing = 0.0;
  spec.landing_before = 1.0;
  return Staircase(spec);
}

// A cycle's input: the body at x, feet under the hips snapped onto the map, all just landed.
StepPlannerInput InputAt(const StepPlanner& planner, double x, double speed) {
  StepPlannerInput in;
  in.body_xy_W = {x, 0.0};
  in.velocity_W = {speed, 0.0};
  for (int l = 0; l < 4; ++l) {
    const Eigen::Vector2d p = planner.NeutralFootXY(l, in.body_xy_W);
    double d = 0.0;
    const int k = planner.NearestRegion(p, &d);
    const Eigen::Vector2d q = planner.SnapIntoRegion(k, p);
    in.legs[static_cast<std::size_t>(l)].foot_W = {q.x(), q.y(), planner.map().stair(k).z};
    in.legs[static_cast<std::size_t>(l)].stair = k;
  }
  return in;
}

int IndexOf(const StepPlanner& planner, double cadence, Gait gait) {
  for (std::size_t i = 0; i < planner.controllers().size(); ++i) {
    const auto& c = planner.controllers()[i];
    if (std::abs(c.cadence_s - cadence) < 1e-12 && c.gait == gait) return static_cast<int>(i);
  }
  return -1;
}

// The worst distance of a controller's unconstrained footsteps from the map's step regions.
double WorstMiss(const ControllerEvaluation& e, const ConstrainedMap& map) {
  double worst = 0.0;
  for (int k = 0; k < e.step_count; ++k) {
    double d = 0.0;
    map.NearestStepRegion(e.steps[static_cast<std::size_t>(k)].unconstrained_xy_W, &d);
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace

TEST_CASE("the default controllers: 5 cadences from 0.25 to 0.45 s times 3 gaits, 8 footsteps", "[step]") {
  const Staircase stairs{StairSpec{}};
  const StepPlanner planner(BuiltinRobot(), ConstrainedMap::FromStaircase(stairs, Facing::kForward));
  REQUIRE(planner.controllers().size() == 15u);
  std::set<double> cadences;
  for (const auto& c : planner.controllers()) cadences.insert(c.cadence_s);
  CHECK(cadences == std::set<double>{0.25, 0.30, 0.35, 0.40, 0.45});
  for (const auto& e : planner.evaluations()) CHECK(e.steps.size() == 8u);
  CHECK(planner.selected() == -1);
}

TEST_CASE("a map where only one cadence lands every footstep in a step region selects it", "[step]") {
  const Staircase stairs = SteppingStones();
  const ConstrainedMap open = OpenMap(stairs);
  const double speed = stairs.spec().run / (4.0 * kCadence);  // the crawl's stride is one tread
  const StepPlanner probe(BuiltinRobot(), open);
  const int target = IndexOf(probe, kCadence, Gait::kCrawl);
  REQUIRE(target >= 0);
  for (double x0 : {0.3, 0.9, 1.77, 2.5}) {
    CAPTURE(x0);
    StepPlanner planner(BuiltinRobot(), open);
    const StepPlannerInput in = InputAt(planner, x0, speed);
    planner.Update(in);
    // Narrow every tread's step region to the target controller's footsteps on it (+/- 2 cm) and
    // remove the regions of treads it does not use.
    std::map<int, std::pair<double, double>> used;
    const ControllerEvaluation& plan = planner.evaluation(target);
    REQUIRE(plan.step_count == 8);
    for (int k = 0; k < plan.step_count; ++k) {
      const Eigen::Vector2d p = plan.steps[static_cast<std::size_t>(k)].unconstrained_xy_W;
      const int s = open.StairAt(p);
      REQUIRE(s >= 0);
      auto [it, fresh] = used.emplace(s, std::make_pair(p.x(), p.x()));
      it->second = {std::min(it->second.first, p.x()), std::max(it->second.second, p.x())};
    }
    ConstrainedMap narrow = open;
    for (int s = 0; s < narrow.size(); ++s) {
      const StairSurface& surface = stairs.surface(s);
      const auto it = used.find(s);
      if (it == used.end()) {
        narrow.AddCollisionBand(s, surface.x_begin - 0.01, surface.x_end + 0.01, RegionKind::kData);
        continue;
      }
      const double lo = it->second.first - 0.02, hi = it->second.second + 0.02;
      if (lo > surface.x_begin) narrow.AddCollisionBand(s, surface.x_begin, lo, RegionKind::kData);
      if (hi < surface.x_end) narrow.AddCollisionBand(s, hi, surface.x_end, RegionKind::kData);
    }
    // The construction does what it says: the target lands everything, every controller of
    // another cadence misses a step region by more than a centimetre somewhere. (The alternative
    // crawl at the same cadence puts the same feet on the same treads, only in another order.)
    CHECK(WorstMiss(plan, narrow) == 0.0);
    int others = 0;
    for (std::size_t i = 0; i < planner.evaluations().size(); ++i) {
      if (planner.controllers()[i].cadence_s == kCadence) continue;
      CHECK(WorstMiss(planner.evaluations()[i], narrow) > 0.01);
      ++others;
    }
    CHECK(others == 12);
    StepPlanner chooser(BuiltinRobot(), narrow);
    const int chosen = chooser.Update(in);
    REQUIRE(chosen >= 0);
    CHECK(chooser.controllers()[static_cast<std::size_t>(chosen)].cadence_s == kCadence);
    CHECK(chooser.selected() == chosen);
    const ControllerEvaluation& best = chooser.evaluation(chosen);
    CHECK(best.admissible);
    CHECK(best.region_cost == 0.0);
    for (int k = 0; k < best.step_count; ++k) {
      const PlannedStep& s = best.steps[static_cast<std::size_t>(k)];
      CHECK(narrow.InStepRegion(s.target_stair, s.target_W.head<2>()));
    }
  }
}

TEST_CASE("no admissible controller: a status with the reason per controller, not a crash", "[step]") {
  // Three steps of `rise` and 0.35 m runs.
  const auto three_steps = [](double rise) {
    StairSpec spec;
    spec.steps = 3;
    spec.rise = rise;
    spec.run = 0.35;
    return Staircase(spec);
  };
  SECTION("risers higher than the robot can step: refused before any cycle") {
    const Staircase stairs = three_steps(0.45);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
    CHECK(plan.status == PlanStatus::kInfeasible);
    CHECK_THAT(plan.status_reason, Catch::Contains("step height") && Catch::Contains("0.450 m"));
    REQUIRE(plan.controllers.size() == 15u);
    for (const ControllerScore& c : plan.controllers) CHECK(c.cycles_selected + c.cycles_ruled_out == 0);
    CHECK(plan.selected == -1);
  }
  SECTION("a tread with no step region: every controller ruled out in a cycle") {
    // Risers the legs can step, but the middle tread is all collision region: the controllers
    // plan the first footsteps, then a foot would have to step two risers (0.4 m) or stay behind.
    const Staircase stairs = three_steps(0.2);
    ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    map.AddCollisionBand(2, stairs.surface(2).x_begin - 0.1, stairs.surface(2).x_end + 0.1, RegionKind::kData);
    const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
    CHECK(plan.status == PlanStatus::kInfeasible);
    CHECK_THAT(plan.status_reason, Catch::Contains("no admissible controller"));
    REQUIRE(plan.controllers.size() == 15u);
    for (const ControllerScore& c : plan.controllers) {
      CAPTURE(ToString(c.gait), c.cadence_s);
      CHECK_FALSE(c.ruled_out_reason.empty());
      CHECK(c.cycles_ruled_out > 0);
      CHECK_THAT(plan.status_reason, Catch::Contains(ToString(c.gait)));
    }
  }
  SECTION("a map without step regions") {
    const Staircase stairs{StairSpec{}};
    ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    for (int s = 0; s < map.size(); ++s) {
      map.AddCollisionBand(s, stairs.surface(s).x_begin - 1.0, stairs.surface(s).x_end + 1.0, RegionKind::kData);
    }
    StepPlanner planner(BuiltinRobot(), map);
    StepPlannerInput in;
    in.velocity_W = {0.15, 0.0};
    for (auto& leg : in.legs) leg.stair = 0;
    CHECK(planner.Update(in) == -1);
    CHECK(planner.selected() == -1);
    for (std::size_t i = 0; i < planner.controllers().size(); ++i) {
      CHECK(planner.evaluations()[i].rule_out == RuleOut::kNoStepRegion);
      CHECK_THAT(planner.RuleOutReason(static_cast<int>(i)), Catch::Contains("no step region"));
    }
    const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map);
    CHECK(plan.status == PlanStatus::kInfeasible);
  }
}

TEST_CASE("selection is deterministic: a tie goes to the lower index", "[step]") {
  // On a long flat landing every controller lands everything: scores differ only in soft terms.
  StairSpec spec;
  spec.steps = 1;
  spec.rise = 0.02;
  spec.nosing = 0.0;
  spec.landing_before = 6.0;
  spec.landing_after = 6.0;
  const Staircase stairs(spec);
  StepPlannerSettings settings;
  settings.cadences_s = {0.3, 0.3, 0.3};  // identical controllers: a pure tie
  settings.gaits = {Gait::kCrawl};
  settings.switch_cost = 0.0;
  settings.gait_switch_cost = 0.0;
  StepPlanner planner(BuiltinRobot(), OpenMap(stairs), settings);
  const StepPlannerInput in = InputAt(planner, -3.0, 0.1);
  CHECK(planner.Update(in) == 0);
  CHECK(planner.evaluation(0).score == planner.evaluation(2).score);
  for (int i = 0; i < 3; ++i) CHECK(planner.Update(in) == 0);
}

TEST_CASE("hysteresis: the switch cost keeps the current controller against a small gain", "[step]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  StepPlanner planner(BuiltinRobot(), map);
  const StepPlannerInput in = InputAt(planner, -0.8, 0.15);
  const int first = planner.Update(in);
  REQUIRE(first >= 0);
  // Same input again: the choice holds, and every other controller carries the switch cost.
  CHECK(planner.Update(in) == first);
  for (std::size_t i = 0; i < planner.evaluations().size(); ++i) {
    const auto& e = planner.evaluations()[i];
    if (!e.admissible) continue;
    const bool same_gait = planner.controllers()[i].gait == planner.controllers()[static_cast<std::size_t>(first)].gait;
    const double expected = static_cast<int>(i) == first ? 0.0
                            : planner.settings().switch_cost + (same_gait ? 0.0 : planner.settings().gait_switch_cost);
    CHECK(e.switch_cost == expected);
  }
}

TEST_CASE("bad settings and input throw naming the field", "[step]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  StepPlannerSettings s;
  s.cadences_s = {0.3, -0.1};
  CHECK_THROWS_WITH(StepPlanner(BuiltinRobot(), map, s), Catch::Contains("cadences_s[1]"));
  s = StepPlannerSettings{};
  s.horizon_steps = 0;
  CHECK_THROWS_WITH(StepPlanner(BuiltinRobot(), map, s), Catch::Contains("horizon_steps"));
  s = StepPlannerSettings{};
  s.reach_min_fraction = 0.96;
  CHECK_THROWS_WITH(StepPlanner(BuiltinRobot(), map, s), Catch::Contains("reach_min_fraction"));
  s = StepPlannerSettings{};
  s.speed = 0.0;
  CHECK_THROWS_WITH(PlanWithStepPlanner(BuiltinRobot(), stairs, map, s), Catch::Contains("speed"));
  StepPlanner planner(BuiltinRobot(), map);
  StepPlannerInput in;
  in.velocity_W = {std::nan(""), 0.0};
  CHECK_THROWS_WITH(planner.Update(in), Catch::Contains("velocity_W"));
}

namespace {

// Stands in for an IK-based reach check: a geometric band narrower than the default, counting
// its queries.
class NarrowReach final : public ReachModel {
 public:
  explicit NarrowReach(double max_fraction) : band_(0.30, max_fraction) {}
  bool Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const override {
    ++queries;
    return band_.Reachable(leg, base_W, foot_W);
  }
  mutable long queries = 0;

 private:
  GeometricReachModel band_;
};

}  // namespace

TEST_CASE("a reach model plugs in without changing the planner", "[step]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  // A tighter reach than the default still plans, and every foot respects it.
  auto tight = std::make_shared<NarrowReach>(0.85);
  const Plan plan = PlanWithStepPlanner(BuiltinRobot(), stairs, map, {}, tight);
  INFO(plan.status_reason);
  REQUIRE(plan.status == PlanStatus::kOk);
  CHECK(tight->queries > 1000);
  for (const Footstep& f : plan.footsteps) {
    CHECK(stairplan::testing::Extension(BuiltinRobot(), plan, f, f.t_touchdown) <= 0.85 + 1e-9);
  }
  // One that reaches nothing rules out every controller on reach (its feet, standing or landing).
  auto none = std::make_shared<NarrowReach>(0.31);
  StepPlanner planner(BuiltinRobot(), map, {}, none);
  const StepPlannerInput in = InputAt(planner, -0.8, 0.15);
  CHECK(planner.Update(in) == -1);
  for (const auto& e : planner.evaluations()) {
    CHECK((e.rule_out == RuleOut::kUnreachable || e.rule_out == RuleOut::kStanceLost));
  }
  CHECK_THAT(planner.RuleOutReason(0), Catch::Contains("reach"));
}
