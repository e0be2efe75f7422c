#include "planning/plan_pipeline.h"

#include <chrono>

namespace stairplan {
namespace {

double MicrosSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

PipelineResult RunPipeline(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options) {
  PipelineResult result;
  const auto t_map = std::chrono::steady_clock::now();
  result.map = ConstrainedMap::FromStaircase(stairs, options.facing, options.map);
  const double map_us = MicrosSince(t_map);
  const auto t_plan = std::chrono::steady_clock::now();
  result.plan = PlanCrawl(robot, stairs, result.map, options.crawl);
  result.plan.timing_us = {{"map", map_us}, {"plan", MicrosSince(t_plan)}};
  return result;
}

}  // namespace stairplan
