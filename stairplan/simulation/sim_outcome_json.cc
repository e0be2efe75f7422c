#include "stairplan/simulation/sim_outcome_json.h"

namespace stairplan {
namespace {

nlohmann::json OutcomeVec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::json SimulationToJson(const SimulationOutcome& o) {
  nlohmann::json j;
  j["status"] = ToString(o.status);
  j["passed"] = o.Passed();
  j["cause"] = o.cause;
  j["first_cause"] = o.FirstCause();
  j["t_end_s"] = o.t_end;
  j["final_base"] = OutcomeVec(o.final_base_W);
  j["final_roll_pitch_yaw"] = OutcomeVec(o.final_rpy);
  j["final_error_m"] = o.final_error_m;
  j["max_roll_rad"] = o.max_roll;
  j["max_pitch_error_rad"] = o.max_pitch_error;
  j["max_height_error_m"] = o.max_height_error;
  j["max_landing_error_m"] = o.MaxLandingError();
  j["all_landed_in_step_regions"] = o.AllLandedInRegions();
  j["landings"] = nlohmann::json::array();
  for (const FootLanding& l : o.landings) {
    j["landings"].push_back({{"leg", l.leg},
                             {"t_planned", l.t_planned},
                             {"t_contact", l.t_contact},
                             {"touched", l.touched},
                             {"target", OutcomeVec(l.target_W)},
                             {"landed", OutcomeVec(l.landed_W)},
                             {"error_m", l.error_m},
                             {"stair", l.stair},
                             {"in_step_region", l.in_step_region}});
  }
  j["other_contacts"] = nlohmann::json::array();
  for (const LinkContact& c : o.other_contacts) {
    j["other_contacts"].push_back({{"link", c.link},
                                   {"stair_geom", c.stair_geom},
                                   {"t_first", c.t_first},
                                   {"max_depth_m", c.max_depth},
                                   {"steps", c.steps}});
  }
  j["impacts"] = nlohmann::json::array();
  for (const ImpactRecord& e : o.impacts) {
    j["impacts"].push_back({{"t", e.t},
                            {"t_contact", e.t_contact},
                            {"t_planned", e.t_planned},
                            {"leg", e.leg},
                            {"kind", ToString(e.kind)},
                            {"source", ToString(e.source)},
                            {"response", ToString(e.response)},
                            {"link", e.link},
                            {"swing_phase", e.swing_phase},
                            {"force_n", e.force_n},
                            {"reason", e.reason},
                            {"at", OutcomeVec(e.at_W)},
                            {"target", OutcomeVec(e.target_W)},
                            {"executed", e.executed}});
  }
  j["min_link_clearance_m"] = o.min_link_clearance_m;
  j["closest_link"] = o.closest_link;
  j["torques"] = nlohmann::json::array();
  for (const JointTorquePeak& t : o.torques) {
    j["torques"].push_back(
        {{"joint", t.joint}, {"peak_nm", t.peak}, {"effort_limit_nm", t.effort_limit}, {"ratio", t.ratio}, {"t", t.t}});
  }
  j["max_torque_ratio"] = o.max_torque_ratio;
  j["time_scale"] = o.time_scale;
  j["force_qp_failures"] = o.force_qp_failures;
  j["stance_forces"] = ToString(o.stance_forces);
  j["max_foot_slip_m"] = o.max_foot_slip_m;
  j["slipped_leg"] = o.slipped_leg;
  j["slip_t_s"] = o.slip_t;
  j["plan_zmp_margin_m"] = o.plan_zmp_margin_m;
  j["plan_zmp_t"] = o.plan_zmp_t;
  j["plan_max_acceleration"] = o.plan_max_acceleration;
  j["sim_steps"] = o.sim_steps;
  j["sim_time_s"] = o.sim_time_s;
  j["wall_time_s"] = o.wall_time_s;
  j["real_time_factor"] = o.real_time_factor;
  return j;
}

nlohmann::json SimFramesToJson(const std::vector<SimFrame>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const SimFrame& f : frames) {
    nlohmann::json q = nlohmann::json::object();
    for (std::size_t i = 0; i < f.legs.size() && i < f.joint_q.size(); ++i) q[f.legs[i]] = OutcomeVec(f.joint_q[i]);
    out.push_back({{"t", f.t}, {"base", OutcomeVec(f.base_W)}, {"roll_pitch_yaw", OutcomeVec(f.base_rpy)}, {"q", q}});
  }
  return out;
}

}  // namespace stairplan
