// What the viewer page shows, as one JSON object: the stairs' solids, the map's step and collision
// regions, the footsteps, the body path, the robot's shapes with their world poses at every frame
// (the plan's, and with a simulation the simulated robot's), and the violations at their place and
// time. It reads plan.json and the simulation's output only; it plans nothing.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan_json_reader.h"

namespace stairplan {

/// How the viewer's scene is sampled.
struct ViewerSceneSettings {
  double frame_period = 0.04;  ///< the plan's robot is posed this often [s]

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// A parsed JSON document and the file it came from (named in errors); json null: none.
struct JsonSource {
  const nlohmann::json* json = nullptr;  ///< the document, or null
  std::string name;  ///< the file it came from
};

/// The scene of `plan_file`, parsed from `plan` (whose map it draws). The violations drawn are those
/// of `validation` (the output of `stairplan validate --json`) or, when that is null, plan.json's own
/// "validation". `sim` is the output of `stairplan simulate --out` with recorded frames, or null.
/// Throws std::invalid_argument naming the file and the field when one is malformed, and naming the
/// link when the robot has geometry the viewer cannot draw.
nlohmann::json BuildViewerScene(const RobotModel& robot, const PlanFile& plan_file, const JsonSource& plan,
                                const JsonSource& validation, const JsonSource& sim,
                                const ViewerSceneSettings& settings = {});

}  // namespace stairplan
