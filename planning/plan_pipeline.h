// The whole planning pipeline for one staircase, in one place so that the CLI, sweeps and tests
// run the same thing: constrained map -> footsteps -> body -> (validation), with stage timings.
#pragma once

#include "geometry/constrained_map.h"
#include "geometry/staircase.h"
#include "kinematics/robot_model.h"
#include "planning/crawl_planner.h"
#include "planning/plan.h"

namespace stairplan {

struct PipelineOptions {
  Facing facing = Facing::kForward;
  ConstrainedMapSettings map;
  CrawlSettings crawl;
};

struct PipelineResult {
  ConstrainedMap map;
  Plan plan;
};

/// Plans `stairs` for `robot`. Throws std::invalid_argument only for invalid options; a staircase
/// the robot cannot traverse gives a plan with status kInfeasible.
PipelineResult RunPipeline(const RobotModel& robot, const Staircase& stairs, const PipelineOptions& options = {});

}  // namespace stairplan
