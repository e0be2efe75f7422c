#include "planning/plan_pipeline.h"

#include <chrono>

namespace stairplan {
namespace {

double MicrosSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ConstrainedMap BuildPipelineMap(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options) {
  ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, options.facing, options.map);
  if (options.robot_regions) {
    const RobotKinematics kinematics(robot);
    const RobotCollisionModel collision(kinematics);
    RobotRegionSettings regions = options.regions;
    regions.hip_height_fraction = options.crawl.body.hip_height_fraction;  // the posture the plan will use
    AddRobotCollisionRegions(kinematics, collision, stairs, map, regions);
  }
  return map;
}

PipelineResult RunPipeline(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options) {
  PipelineResult result;
  const auto t_map = std::chrono::steady_clock::now();
  result.map = BuildPipelineMap(robot, stairs, options);
  const double map_us = MicrosSince(t_map);
  const auto t_plan = std::chrono::steady_clock::now();
  result.plan = PlanCrawl(robot, stairs, result.map, options.crawl);
  result.plan.timing_us = {{"map", map_us}, {"plan", MicrosSince(t_plan)}};
  if (options.validate && result.plan.status == PlanStatus::kOk) {
    const auto t_validate = std::chrono::steady_clock::now();
    TraversalValidator validator(robot, stairs, result.map, options.validation);
    result.validation = validator.Validate(result.plan);
    result.validated = true;
    result.plan.timing_us.emplace_back("validate", MicrosSince(t_validate));
  }
  return result;
}

}  // namespace stairplan
