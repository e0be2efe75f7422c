// Perception feeds planning (seed 000 claim 1; acceptance 4): a crawl planned on the stairs and
// the constrained map perceived from a camera cloud, moved back into the true stairs' frame,
// passes the validator on the true stairs (and on what was perceived).
#include <catch2/catch.hpp>

#include <string>

#include "stairplan/collision/robot_collision_regions.h"
#include "stairplan/perception/depth_sensor.h"
#include "stairplan/perception/stair_perception.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "perception/perception_scenes.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/validation/traversal_validator.h"
#include "leg_row_pipeline.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

std::string Describe(const ValidationReport& r) {
  std::string text = "min clearance " + std::to_string(r.min_clearance_m) + ", violations:";
  for (const Violation& v : r.violations) {
    text += "\n  t=" + std::to_string(v.t) + " " + v.leg + " " + ToString(v.kind) + " " + std::to_string(v.value) + " " + v.detail;
  }
  return text;
}

// A plan made in the fitted stairs' frame, expressed in the world (here the true stairs' frame).
// Feet land on the real surface: a touchdown stops where the foot meets the ground, so contact
// heights are those of the true treads under the planned footholds (a few millimetres from the
// perceived ones); the body keeps its planned heights.
Plan ToWorld(const Plan& plan, const StairModel& model, TravelDirection travel, const Staircase& truth) {
  const auto world = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3d w = model.StairToWorld(p, travel);
    const double ground = truth.HeightAt(w.x(), w.y());
    if (!std::isnan(ground)) w.z() = ground;
    return w;
  };
  const double base_z = model.levels.front();
  Plan out = plan;
  for (auto& p : out.initial_feet_W) p = world(p);
  for (Footstep& f : out.footsteps) {
    f.position_W = world(f.position_W);
    f.from_W = world(f.from_W);
    if (!std::isnan(f.swing_apex_z)) f.swing_apex_z += base_z;
  }
  const double yaw = model.TravelYaw(travel);
  for (BodyState& b : out.body) {
    const Eigen::Vector3d p = model.StairToWorld(Eigen::Vector3d(b.x, b.y, b.z), travel);
    b.x = p.x();
    b.y = p.y();
    b.z = p.z();
    b.yaw += yaw;
  }
  return out;
}

}  // namespace

TEST_CASE("a crawl planned on the perceived map validates on the true stairs", "[perception][plan]") {
  const Staircase truth(StairSpec{});
  const RobotModel robot = BuiltinRobot();
  const RobotKinematics kinematics(robot);
  const RobotCollisionModel collision(kinematics);
  PipelineOptions options;
  RobotRegionSettings regions = options.regions;
  regions.hip_height_fraction = options.crawl.body.hip_height_fraction;
  const ConstrainedMap truth_map = BuildPipelineMap(robot, truth, options);
  TraversalValidator on_truth(robot, truth, truth_map);
  // Under the sanitizers one noisy scan (60 s for four there): the same perception, crawl and
  // validation code runs for every seed; the normal build keeps the four.
  const std::uint32_t seeds = stairplan::testing::FullOrSanitized(4u, 1u);
  for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
    SensorNoise noise;
    noise.range_sigma = 0.005;
    noise.seed = seed;
    const PointCloud cloud = ScanStairs(truth, PinholeCamera{}, stairplan::testing::CameraOnBottomLanding(), noise);
    const StairPerception seen = PerceiveStairs(cloud);
    INFO("seed " << seed);
    REQUIRE(seen.stairs.has_value());
    // What `stairplan plan --cloud` does: the perceived map, then this robot's own regions on it.
    ConstrainedMap map = seen.stairs->map;
    AddRobotCollisionRegions(kinematics, collision, seen.stairs->stairs, map, regions);
    const Plan plan = PlanCrawl(robot, seen.stairs->stairs, map, options.crawl);
    INFO(plan.status_reason);
    REQUIRE(plan.status == PlanStatus::kOk);
    TraversalValidator on_seen(robot, seen.stairs->stairs, map);
    const ValidationReport self = on_seen.Validate(plan);
    INFO("on the perceived stairs: " << Describe(self));
    CHECK(self.ok);
    const ValidationReport report = on_truth.Validate(ToWorld(plan, seen.fit.model, TravelDirection::kUp, truth));
    INFO("on the true stairs: " << Describe(report));
    CHECK(report.ok);
  }
}

// `plan --cloud --direction down` (#18 acceptance 3): a depth camera on the top landing looking
// down the flight sees each tread's far part (gap filling fills the rest flat behind the nosing
// above it); the pipeline plans on the perceived stairs and map, and its plan, moved into the true
// stairs' frame, validates there too. With the body optimisation: the quasi-static path's posture
// retries run on known stairs only, and its plans on these maps put a front leg out of reach.
TEST_CASE("a descent the body optimisation plans on the perceived map validates on the true stairs", "[perception][plan]") {
  // Normal build only: its code runs sanitized in "plan --cloud plans on the perceived stairs"
  // (perception, then the pipeline on the perceived map) and in "the built-in robot's default
  // descents validate" (the body optimisation down the stairs); here it took 94 s there.
  if (stairplan::testing::kSanitized) return;
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase truth(spec);
  const RobotModel robot = BuiltinRobot();
  const PipelineOptions options = stairplan::testing::LegRowPipeline();
  const ConstrainedMap truth_map = BuildPipelineMap(robot, truth, options);
  TraversalValidator on_truth(robot, truth, truth_map);
  StairPerceptionSettings settings;
  settings.regions.travel = TravelDirection::kDown;
  // One noisy scan (the climb above runs four through the same perception code): a whole-flight
  // body optimisation takes seconds a plan. Seeds 2 and 3 pass too.
  SensorNoise noise;
  noise.range_sigma = 0.005;
  noise.seed = 1;
  const PointCloud cloud = ScanStairs(truth, stairplan::testing::VgaCamera(), stairplan::testing::CameraOnTopLanding(truth), noise);
  const StairPerception seen = PerceiveStairs(cloud, settings);
  REQUIRE(seen.stairs.has_value());
  CHECK(seen.stairs->stairs.direction() == TravelDirection::kDown);
  CHECK(seen.stairs->stairs.steps() == truth.steps());
  // What `stairplan plan --cloud` does: this robot's own regions on the perceived map, then the pipeline.
  ConstrainedMap map = seen.stairs->map;
  AddPipelineRobotRegions(robot, seen.stairs->stairs, options, map);
  const PipelineResult r = RunPipelineOnMap(robot, seen.stairs->stairs, map, options);
  INFO(r.plan.status_reason);
  REQUIRE(r.plan.status == PlanStatus::kOk);
  CHECK(r.plan.body_planner == BodyPlannerKind::kRecedingHorizonQp);
  INFO("on the perceived stairs: " << Describe(r.validation));
  CHECK(r.validation.ok);
  const ValidationReport report = on_truth.Validate(ToWorld(r.plan, seen.fit.model, TravelDirection::kDown, truth));
  INFO("on the true stairs: " << Describe(report));
  CHECK(report.ok);
}
