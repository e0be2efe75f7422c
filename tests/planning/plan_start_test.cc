// The plan starts at the alignment pose, and stair mode is judged at the robot's tracked pose
// (seed 001 [0042]-[0043], claim 7; issue #26): the default flight placed yawed and offset in a
// world, as a cloud or footfalls find one, and a robot standing yawed and off the centre line
// before it. The crawl's first body state is the alignment pose the patent's function gives for
// those stairs, at the stance's standoff; its feet stand in the nominal stance; the plan validates.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/stair_mode.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

// The default flight, traversed `travel`, ascending along yaw 0.7 from (2, -1, 0.3).
StairFrame PlacedDefaultFlight(TravelDirection travel) {
  StairSpec spec;
  spec.direction = travel;
  return {ModelOfStaircase(Staircase(spec), Eigen::Vector3d(2.0, -1.0, 0.3), 0.7), travel, spec.nosing};
}

double AngleBetween(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

GroundPose FirstBodyPose(const Plan& plan) {
  GroundPose p;
  p.xy << plan.body.front().x, plan.body.front().y;
  p.yaw = plan.body.front().yaw;
  return p;
}

// A robot `before` metres short of the flight's first edge along the travel, `aside` to its left,
// turned `turn` from the travel: in the world, then in the plan's frame.
GroundPose RobotBefore(const StairFrame& frame, const Staircase& stairs, double before, double aside, double turn) {
  GroundPose s;
  s.xy << stairs.edges().front().x_nose - before, aside;
  s.yaw = turn;
  const GroundPose w = frame.ToWorld(s);
  return frame.ToStair(w);
}

}  // namespace

TEST_CASE("the plan starts at the alignment pose for a yawed, offset robot, up and down", "[plan][alignment]") {
  const RobotModel& robot = BuiltinRobot();
  // Under the sanitizers the climb only (the descent adds no code path, and plans twice as long).
  const int directions = testing::FullOrSanitized(2, 1);
  for (int d = 0; d < directions; ++d) {
    const TravelDirection travel = d == 0 ? TravelDirection::kUp : TravelDirection::kDown;
    INFO(ToString(travel));
    const StairFrame frame = PlacedDefaultFlight(travel);
    const Staircase stairs = frame.model.ToStaircase(travel, frame.nosing);
    PipelineOptions options;
    options.start_at_alignment = true;
    options.robot_pose = RobotBefore(frame, stairs, 0.8, 0.3, 0.9);
    const PipelineResult r = RunPipeline(robot, stairs, options);
    REQUIRE(r.plan.status == PlanStatus::kOk);
    REQUIRE(r.validated);
    CHECK(r.validation.ok);
    const AlignmentStance& a = r.approach.alignment;
    REQUIRE(a.found);
    // Stair mode: on, 0.8 m from the flight; the robot turns 0.9 rad back and moves to the pose.
    CHECK(r.approach.robot_known());
    CHECK(r.approach.robot_source == RobotPoseSource::kGiven);
    CHECK(r.approach.stair_mode.engaged);
    CHECK(r.approach.stair_mode.distance == Approx(0.8));
    CHECK(r.approach.turn == Approx(-0.9));
    CHECK(r.approach.move.y() == Approx(-0.3));
    // The plan's first body state is the alignment pose: centred, heading along the travel.
    const GroundPose first = FirstBodyPose(r.plan);
    CHECK(std::abs(first.xy.x() - a.position.x()) < 0.002);
    CHECK(std::abs(first.xy.y()) < 0.002);
    CHECK(AngleBetween(first.yaw, 0.0) < 1e-9);
    CHECK(-first.xy.x() == Approx(a.riser_distance).margin(0.002));
    CHECK(a.standoff == Approx(a.riser_distance + stairs.edges().front().x_nose));
    // In the world it is the patent's alignment pose for the stairs at that standoff.
    const GroundPose first_W = frame.ToWorld(first);
    const AlignmentPose patent = ComputeAlignmentPose(frame.model, travel, Facing::kForward, a.standoff);
    CHECK((first_W.xy - patent.position.head<2>()).norm() < 0.002);
    CHECK(AngleBetween(first_W.yaw, patent.yaw) < 1e-9);
    CHECK(AngleBetween(first_W.yaw, frame.model.TravelYaw(travel)) < 1e-9);
    // The feet start in the stance: spaced as the hips are, the leading ones the crawl's start
    // gap before the end of the landing's step region, every one on the landing.
    REQUIRE(r.plan.initial_feet_W.size() == robot.legs().size());
    const Extent landing = r.map.stair(0).step_region.XExtent();
    double lead = -1e9;
    for (std::size_t i = 0; i < robot.legs().size(); ++i) {
      CHECK((r.plan.initial_feet_W[i] - a.feet[i]).norm() < 1e-12);
      const Eigen::Vector3d rel = a.feet[i] - a.feet[0];
      CHECK(rel.x() == Approx(robot.legs()[i].hip_B.x() - robot.legs()[0].hip_B.x()).margin(1e-9));
      CHECK(rel.y() == Approx(robot.legs()[i].foot_zero_B.y() - robot.legs()[0].foot_zero_B.y()).margin(1e-9));
      CHECK(r.map.StairAt(a.feet[i].head<2>()) == 0);
      lead = std::max(lead, a.feet[i].x());
    }
    CHECK(lead == Approx(landing.hi - options.crawl.start_gap));
  }
}

TEST_CASE("stair mode is off beyond the engage distance and on within it, and the plan starts at the alignment pose either way", "[plan][alignment]") {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs{StairSpec{}};
  const StairFrame frame{ModelOfStaircase(stairs, Eigen::Vector3d::Zero(), 0.0), TravelDirection::kUp, stairs.spec().nosing};
  PipelineOptions options;
  options.start_at_alignment = true;
  options.robot_pose = RobotBefore(frame, stairs, 3.0, -0.2, 2.0);
  const PipelineResult far = RunPipeline(robot, stairs, options);
  REQUIRE(far.plan.status == PlanStatus::kOk);
  CHECK_FALSE(far.approach.stair_mode.engaged);
  CHECK(far.approach.stair_mode.distance == Approx(3.0));
  const AlignmentStance& a = far.approach.alignment;
  REQUIRE(a.found);
  CHECK(PlanStartOffset(far.plan, a).distance < 0.002);
  CHECK(std::abs(PlanStartOffset(far.plan, a).yaw) < 1e-9);
  // The switch at the threshold, and a robot given no pose stands at the alignment pose: on.
  for (const double before : {0.98, 1.02}) {
    const StairApproach at = ApproachStairs(stairs, a, RobotBefore(frame, stairs, before, 0.0, 0.0), options.stair_mode);
    CHECK(at.stair_mode.engaged == (before < 1.0));
  }
  StairModeSettings near;
  near.engage_distance = 0.2;  // closer than the standoff: even the alignment pose is out of range
  CHECK_FALSE(ApproachStairs(stairs, a, std::nullopt, near).stair_mode.engaged);
  const StairApproach none = ApproachStairs(stairs, a, std::nullopt, options.stair_mode);
  CHECK(none.stair_mode.engaged);
  CHECK_FALSE(none.robot_known());
  CHECK(none.robot_source == RobotPoseSource::kAlignment);
  CHECK(none.stair_mode.distance == Approx(a.standoff));
  CHECK(none.move.norm() == 0.0);
}

TEST_CASE("the alignment stance facing backward: turned round, the COM over the centre of the feet", "[plan][alignment]") {
  const RobotModel& robot = BuiltinRobot();
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  PipelineOptions options;
  options.facing = Facing::kBackward;
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
  const double hip = options.crawl.body.hip_height_fraction, gap = options.crawl.start_gap;
  const RobotKinematics kinematics(robot);
  const AlignmentStance back = ComputeAlignmentStance(kinematics, stairs, map, Facing::kBackward, hip, gap);
  REQUIRE(back.found);
  CHECK(back.yaw == Approx(M_PI));
  // Descending backwards (seed 001 [0042]) the body heads up the stairs in the world.
  const StairFrame frame{ModelOfStaircase(stairs, Eigen::Vector3d(0.0, 0.0, 0.0), 0.4), TravelDirection::kDown, spec.nosing};
  GroundPose pose;
  pose.xy = back.position.head<2>();
  pose.yaw = back.yaw;
  CHECK(AngleBetween(frame.ToWorld(pose).yaw, frame.model.yaw()) < 1e-9);
  CHECK(AngleBetween(frame.ToWorld(pose).yaw, ComputeAlignmentPose(frame.model, TravelDirection::kDown, Facing::kBackward, back.standoff).yaw) < 1e-9);
  // The hind hips lead: the feet under them are the leading ones, and the stance is the forward
  // one turned round (its centre shifted by the same COM offset, mirrored).
  const AlignmentStance fwd = ComputeAlignmentStance(kinematics, stairs, map, Facing::kForward, hip, gap);
  REQUIRE(fwd.found);
  for (std::size_t i = 0; i < robot.legs().size(); ++i) {
    const Eigen::Vector3d b = back.feet[i] - back.position, f = fwd.feet[i] - fwd.position;
    CHECK(b.x() == Approx(-f.x()).margin(1e-9));
    CHECK(b.y() == Approx(-f.y()).margin(1e-9));
  }
  // A landing too short for the stance is said so, not planned on.
  spec.landing_before = 0.3;
  const Staircase short_landing(spec);
  const AlignmentStance none =
      ComputeAlignmentStance(kinematics, short_landing, BuildPipelineMap(robot, short_landing, options), Facing::kBackward, hip, gap);
  CHECK_FALSE(none.found);
  CHECK_THAT(none.reason, Catch::Contains("landing_before"));
}
