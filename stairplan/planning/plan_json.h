// plan.json: the plan as one JSON object. The key names are a stable interface.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/planner_clearances.h"
#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan {

/// The resolved staircase as JSON (spec fields plus per-surface geometry).
nlohmann::json StairsToJson(const Staircase& stairs);
/// The validator's report: ok, min_clearance_m, min_stability_margin_m, samples, dynamics {mode,
/// torque_limits_checked, body_inertia_known, friction, tolerance_n, max_residual_n, max_residual_t,
/// failed_instants, first_failure {t, kind, leg} when one fails}, violations [{t, leg, kind, family,
/// value, detail}].
nlohmann::json ValidationToJson(const ValidationReport& report);

/// plan.json's `clearance`: the margins the planners kept (stairs_uncertainty_m, body_qp_margin_m,
/// touchdown_m, swing_m, edge_margin_m, riser_margin_m) and the validator's (validator_min_m).
nlohmann::json ClearancesToJson(const PlannerClearances& clearances);
/// The whole plan: robot, stairs, map regions, footsteps, body, cadence, status, timings, and the
/// version and schema_version of the writer.
nlohmann::json PlanToJson(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map);

}  // namespace stairplan
