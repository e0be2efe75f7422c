// The alignment stance stands the robot with the planner's kinematics (stairplan/planning/stair_alignment.h):
// it builds no KDL tree and leg chains of its own, which every plan would pay for again.
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/stair_alignment.h"

using namespace stairplan;

TEST_CASE("the alignment stance builds no kinematics of its own", "[plan][alignment][alloc]") {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs{StairSpec{}};
  const PipelineOptions options;
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
  std::size_t build = 0;
  {
    const testing::AllocationScope scope;
    const RobotKinematics built(robot);
    build = scope.count();
  }
  const RobotKinematics kinematics(robot);
  std::size_t stance = 0;
  AlignmentStance a;
  {
    const testing::AllocationScope scope;
    a = ComputeAlignmentStance(kinematics, stairs, map, Facing::kForward, options.crawl.body.hip_height_fraction,
                               options.crawl.start_gap);
    stance = scope.count();
  }
  REQUIRE(a.found);
  INFO("allocations: building the kinematics " << build << ", the alignment stance " << stance);
  CHECK(stance < build);
}
