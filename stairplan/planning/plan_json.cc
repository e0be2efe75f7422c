#include "stairplan/planning/plan_json.h"

#include <algorithm>
#include <cmath>

#include "stairplan/planning/json_version.h"
#include "stairplan/planning/plan_timeline.h"

namespace stairplan {
namespace {

nlohmann::json PolygonToJson(const Polygon2& poly) {
  nlohmann::json points = nlohmann::json::array();
  for (const auto& v : poly.vertices) points.push_back({v.x(), v.y()});
  return points;
}

nlohmann::json MapToJson(const ConstrainedMap& map) {
  nlohmann::json stairs = nlohmann::json::array();
  for (const StairRegions& s : map.stairs()) {
    nlohmann::json collisions = nlohmann::json::array();
    for (const CollisionRegion& c : s.collision_regions) {
      collisions.push_back({{"kind", ToString(c.kind)}, {"polygon", PolygonToJson(c.polygon)}});
    }
    stairs.push_back({{"index", s.index}, {"z", s.z}, {"step_region", PolygonToJson(s.step_region)},
                      {"collision_regions", collisions}});
  }
  return {{"facing", ToString(map.facing())}, {"stairs", stairs}};
}

}  // namespace

nlohmann::json StairsToJson(const Staircase& stairs) {
  const StairSpec& spec = stairs.spec();
  nlohmann::json surfaces = nlohmann::json::array();
  for (const StairSurface& s : stairs.surfaces()) {
    surfaces.push_back({{"index", s.index}, {"x_begin", s.x_begin}, {"x_end", s.x_end}, {"z", s.z}});
  }
  return {{"steps", spec.steps},       {"rise", spec.rise},
          {"run", spec.run},           {"nosing", spec.nosing},
          {"width", spec.width},       {"landing_before", spec.landing_before},
          {"landing_after", spec.landing_after}, {"nosing_thickness", spec.nosing_thickness},
          {"rises", spec.rises},       {"runs", spec.runs},
          {"direction", ToString(spec.direction)}, {"total_rise", stairs.total_rise()},
          {"surfaces", surfaces}, {"uncertainty", spec.uncertainty}};
}

nlohmann::json ClearancesToJson(const PlannerClearances& c) {
  return {{"stairs_uncertainty_m", c.stairs_uncertainty}, {"body_qp_margin_m", c.body_qp}, {"touchdown_m", c.touchdown},
          {"swing_m", c.swing}, {"edge_margin_m", c.edge_margin}, {"riser_margin_m", c.riser_margin},
          {"validator_min_m", c.validator}};
}

nlohmann::json ValidationToJson(const ValidationReport& report) {
  nlohmann::json violations = nlohmann::json::array();
  for (const Violation& v : report.violations) {
    violations.push_back({{"t", v.t}, {"leg", v.leg}, {"kind", ToString(v.kind)}, {"family", ToString(FamilyOf(v.kind))},
                          {"value", v.value}, {"worst", v.worst}, {"t_worst", v.t_worst}, {"detail", v.detail}});
  }
  const auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  const DynamicsReport& d = report.dynamics;
  nlohmann::json dynamics = {{"mode", ToString(d.mode)}, {"torque_limits_checked", d.torque_limits_checked},
                             {"body_inertia_known", d.body_inertia_known}, {"friction", d.friction},
                             {"tolerance_n", d.tolerance_n}, {"max_residual_n", finite(d.max_residual_n)},
                             {"max_residual_t", d.max_residual_t}, {"failed_instants", d.failed_instants},
                             {"max_line_tilt_rad", d.max_line_tilt_rad}, {"max_line_tilt_t", d.max_line_tilt_t}};
  if (d.failed_instants > 0) {
    dynamics["first_failure"] = {{"t", d.first_failure_t}, {"kind", ToString(d.first_failure_kind)},
                                 {"leg", ToString(d.first_failure_leg)}};
  }
  return {{"ok", report.ok}, {"min_clearance_m", finite(report.min_clearance_m)},
          {"min_stability_margin_m", finite(report.min_stability_margin_m)}, {"samples", report.samples},
          {"dynamics", dynamics}, {"violations", violations}};
}

namespace {

// The receding horizon's cycles: a summary, then one array per statistic (one entry per cycle).
nlohmann::json BodyCyclesToJson(const std::vector<BodyCycleStats>& cycles) {
  nlohmann::json t = nlohmann::json::array(), status = t, solves = t, iterations = t, solve_us = t, total_us = t,
                 relaxation = t;
  int stale = 0, infeasible = 0, max_iterations = 0;
  double iteration_sum = 0.0;
  std::vector<double> solve_times;
  solve_times.reserve(cycles.size());
  for (const BodyCycleStats& c : cycles) {
    t.push_back(c.t);
    status.push_back(ToString(c.status));
    solves.push_back(c.solves);
    iterations.push_back(c.iterations);
    solve_us.push_back(c.solve_us);
    total_us.push_back(c.total_us);
    relaxation.push_back(c.relaxation);
    stale += c.status == BodyPlanStatus::kStale ? 1 : 0;
    infeasible += c.status == BodyPlanStatus::kInfeasible ? 1 : 0;
    max_iterations = std::max(max_iterations, c.iterations);
    iteration_sum += c.iterations;
    solve_times.push_back(c.solve_us);
  }
  std::sort(solve_times.begin(), solve_times.end());
  const auto quantile = [&](double q) {
    return solve_times.empty() ? 0.0 : solve_times[static_cast<std::size_t>(q * static_cast<double>(solve_times.size() - 1))];
  };
  const double n = std::max<double>(1.0, static_cast<double>(cycles.size()));
  return {{"count", cycles.size()},
          {"stale", stale},
          {"infeasible", infeasible},
          {"relaxed", SummariseRelaxed(cycles).count},
          {"iterations_mean", iteration_sum / n},
          {"iterations_max", max_iterations},
          {"solve_us_p50", quantile(0.5)},
          {"solve_us_p99", quantile(0.99)},
          {"solve_us_max", quantile(1.0)},
          {"per_cycle",
           {{"t", t}, {"status", status}, {"solves", solves}, {"iterations", iterations}, {"solve_us", solve_us},
            {"total_us", total_us}, {"relaxation", relaxation}}}};
}

}  // namespace

nlohmann::json PlanToJson(const Plan& plan, const Staircase& stairs, const ConstrainedMap& map) {
  nlohmann::json footsteps = nlohmann::json::array();
  for (const Footstep& f : plan.footsteps) {
    footsteps.push_back({{"leg", f.leg}, {"t_liftoff", f.t_liftoff}, {"t_touchdown", f.t_touchdown},
                         {"x", f.position_W.x()}, {"y", f.position_W.y()}, {"z", f.position_W.z()},
                         {"stair_index", f.stair_index}, {"in_step_region", f.in_step_region},
                         {"swing_apex_z", std::isfinite(f.swing_apex_z) ? nlohmann::json(f.swing_apex_z) : nlohmann::json(nullptr)}});
    // Only the swings that need it carry it: plans of the lift-first swing stay as they were.
    if (f.swing_approach_share > 0.0) footsteps.back()["swing_approach_share"] = f.swing_approach_share;
  }
  nlohmann::json initial = nlohmann::json::array();
  for (std::size_t i = 0; i < plan.initial_feet_W.size(); ++i) {
    const auto& p = plan.initial_feet_W[i];
    initial.push_back({{"leg", plan.legs.at(i)}, {"x", p.x()}, {"y", p.y()}, {"z", p.z()}});
  }
  nlohmann::json body = nlohmann::json::array();
  for (const BodyState& b : plan.body) {
    body.push_back({{"t", b.t}, {"x", b.x}, {"y", b.y}, {"z", b.z}, {"pitch", b.pitch}, {"yaw", b.yaw},
                    {"com_shift", b.com_shift}, {"com_shift_y", b.com_shift_y}});
  }
  nlohmann::json controllers = nlohmann::json::array();
  for (const ControllerScore& c : plan.controllers) {
    controllers.push_back({{"cadence_s", c.cadence_s}, {"gait", ToString(c.gait)},
                           {"score", std::isfinite(c.score) ? nlohmann::json(c.score) : nlohmann::json(nullptr)},
                           {"ruled_out_reason", c.ruled_out_reason}, {"cycles_selected", c.cycles_selected},
                           {"cycles_ruled_out", c.cycles_ruled_out}});
  }
  nlohmann::json rejected = nlohmann::json::array();
  for (const GaitRejection& g : plan.rejected_gaits) rejected.push_back({{"gait", ToString(g.gait)}, {"reason", g.reason}});
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [stage, us] : plan.timing_us) timing[stage] = us;
  nlohmann::json out = {{"robot", {{"name", plan.robot_name}, {"source", plan.robot_source}, {"legs", plan.legs}}},
                         {"stairs", StairsToJson(stairs)},
                         {"facing", ToString(plan.facing)},
                         {"map", MapToJson(map)},
                         {"gait", GaitName(plan.gait)},
                         {"rejected_gaits", rejected},
                         {"cadence_s", plan.cadence_s},
                         {"hip_height_fraction", std::isfinite(plan.hip_height_fraction) ? nlohmann::json(plan.hip_height_fraction)
                                                                                         : nlohmann::json(nullptr)},
                         {"initial_feet", initial},
                         {"footsteps", footsteps},
                         {"body", body},
                         {"body_planner", ToString(plan.body_planner)},
                         {"body_cycles", BodyCyclesToJson(plan.body_cycles)},
                         {"duration_s", plan.duration()},
                         {"flight_s", FlightDuration(plan)},
                         {"speed_m_s", TravelSpeed(plan)},
                         {"status", ToString(plan.status)},
                         {"status_reason", plan.status_reason},
                         {"timing_us", timing},
                         {"controllers", controllers},
                         {"selected", plan.selected}};
  return StampVersion(out);
}

}  // namespace stairplan
