// The one place where the Python API meets the planning pipeline: its keyword options mapped onto
// PipelineOptions and the stairs with the CLI's names and defaults (`stairplan plan`), and the
// pipeline's entry points. When the pipeline changes, this file changes and the bindings do not.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/pipeline/plan_pipeline.h"

namespace stairplan::python {

/// The stair fields a call may give on top of a stairs file or dict (the CLI's stair flags).
const std::vector<std::string>& StairOptionNames();

/// Options of plan() and sweep() as JSON {name: value}: facing, planner, gait, body, horizon, nlp,
/// validate, validation_time_step. Absent or null ones keep the CLI's defaults. Throws FieldError
/// naming the option for a bad value or an unknown name.
PipelineOptions PipelineOptionsFrom(const nlohmann::json& options);

/// plan()'s `start`, the CLI's --start: the robot's pose (x, y, yaw) [m, m, rad] in `world` when the
/// stairs were found there (a Perception; may be null: in the stairs' own frame), into `options`
/// (robot_pose, its source "given"). Null keeps none. Throws FieldError naming start.
void SetRobotStart(const nlohmann::json& start, const StairFrame* world, PipelineOptions& options);

/// A StairSpec from an object of stairs YAML keys (checked as the YAML reader checks a file).
/// Throws FieldError naming `source` and the field.
StairSpec StairSpecFrom(const nlohmann::json& fields, const std::string& source);

/// The stairs `base` with the stair fields of `overrides` on top, a scalar override (or a new step
/// count) replacing the per-step list of the same quantity as the CLI's flags do. Throws
/// FieldError naming `source` and the field.
Staircase StairsFrom(StairSpec base, const nlohmann::json& overrides, const std::string& source);

}  // namespace stairplan::python

#include "stairplan/sweep/sweep_runner.h"

namespace stairplan::python {

/// Plans `stairs` for `robot` with `options`, on `perceived_map` (the robot's regions added) when
/// given, else on the map the pipeline builds. Call without the GIL.
PipelineResult RunPlanPipeline(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap* perceived_map,
                               const PipelineOptions& options);

/// One sweep point through the pipeline with `options`, as `stairplan sweep` evaluates it (that
/// command's physics aside): never throws; bad stairs give the row status "bad_stairs".
SweepRow EvaluateSweepPoint(const SweepPoint& point, const RobotModel& robot, const PipelineOptions& options);

}  // namespace stairplan::python
