#include "stairplan/planning/plan_json_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "stairplan/planning/json_field_reader.h"
#include "stairplan/version.h"

namespace stairplan {
namespace {

using nlohmann::json;

using Reader = JsonFieldReader;

std::vector<double> Numbers(const Reader& r, const json& node, const std::string& key, const std::string& path) {
  std::vector<double> values;
  if (!node.contains(key)) return values;
  const json& list = r.Array(node, key, path);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number() || !std::isfinite(list[i].get<double>())) {
      r.Fail(path + key + "[" + std::to_string(i) + "]", "must be a finite number");
    }
    values.push_back(list[i].get<double>());
  }
  return values;
}

StairSpec ReadStairs(const Reader& r, const json& node) {
  const std::string p = "stairs.";
  StairSpec spec;
  const double steps = r.Number(node, "steps", p);
  if (steps != std::floor(steps) || steps < 1 || steps > 200) r.Fail(p + "steps", "must be a whole number from 1 to 200");
  spec.steps = static_cast<int>(steps);
  spec.rise = r.Number(node, "rise", p);
  spec.run = r.Number(node, "run", p);
  spec.nosing = r.Number(node, "nosing", p);
  spec.width = r.Number(node, "width", p);
  spec.landing_before = r.Number(node, "landing_before", p);
  spec.landing_after = r.Number(node, "landing_after", p);
  if (node.contains("nosing_thickness")) spec.nosing_thickness = r.Number(node, "nosing_thickness", p);
  if (node.contains("uncertainty")) spec.uncertainty = r.Number(node, "uncertainty", p);
  spec.rises = Numbers(r, node, "rises", p);
  spec.runs = Numbers(r, node, "runs", p);
  try {
    spec.direction = ParseDirection(r.Text(node, "direction", p), "direction");
    spec.Validate();
  } catch (const FieldError& e) {
    r.Fail(p + e.field(), e.problem());
  }
  return spec;
}

Footstep ReadFootstep(const Reader& r, const json& node, const std::string& path) {
  Footstep f;
  f.leg = r.Text(node, "leg", path);
  f.t_touchdown = r.Number(node, "t_touchdown", path);
  f.t_liftoff = node.contains("t_liftoff") ? r.Number(node, "t_liftoff", path) : f.t_touchdown;
  if (f.t_liftoff > f.t_touchdown) r.Fail(path + "t_liftoff", "is after t_touchdown");
  f.position_W = r.Point(node, path);
  if (node.contains("from")) f.from_W = r.Point(r.At(node, "from", path), path + "from.");
  if (node.contains("swing_apex_z") && !node.at("swing_apex_z").is_null()) f.swing_apex_z = r.Number(node, "swing_apex_z", path);
  if (node.contains("swing_approach_share")) {
    f.swing_approach_share = r.Number(node, "swing_approach_share", path);
    if (!(f.swing_approach_share >= 0.0 && f.swing_approach_share < 1.0)) r.Fail(path + "swing_approach_share", "must be in [0, 1)");
  }
  if (node.contains("stair_index")) {
    // Checked before the cast: a double outside int's range is undefined behaviour (UBSan).
    const double index = r.Number(node, "stair_index", path);
    if (index != std::floor(index) || index < -1 || index > 1e6) r.Fail(path + "stair_index", "must be a whole number from -1");
    f.stair_index = static_cast<int>(index);
  }
  if (node.contains("in_step_region") && node.at("in_step_region").is_boolean()) f.in_step_region = node.at("in_step_region").get<bool>();
  return f;
}

BodyState ReadBody(const Reader& r, const json& node, const std::string& path) {
  BodyState b;
  b.t = r.Number(node, "t", path);
  b.x = r.Number(node, "x", path);
  b.z = r.Number(node, "z", path);
  b.pitch = r.Number(node, "pitch", path);
  if (node.contains("y")) b.y = r.Number(node, "y", path);
  if (node.contains("yaw")) b.yaw = r.Number(node, "yaw", path);
  if (node.contains("com_shift")) b.com_shift = r.Number(node, "com_shift", path);
  if (node.contains("com_shift_y")) b.com_shift_y = r.Number(node, "com_shift_y", path);
  return b;
}

// A footstep's starting foothold: the same leg's previous touchdown (or its initial foot).
void LinkFootholds(Plan& plan) {
  std::vector<Eigen::Vector3d> last = plan.initial_feet_W;
  for (Footstep& f : plan.footsteps) {
    const auto i = static_cast<std::size_t>(std::find(plan.legs.begin(), plan.legs.end(), f.leg) - plan.legs.begin());
    if (i >= last.size()) continue;
    if (f.from_W.isZero()) f.from_W = last[i];
    last[i] = f.position_W;
  }
}

}  // namespace

PlanFile ReadPlanJson(const std::string& text, const std::string& source) {
  const Reader r(source);
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(source + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const json::out_of_range&) {
    // The parser's own number overflow (e.g. 1e400), found by the fuzzer.
    throw std::invalid_argument(source + ": not valid JSON (a number too large for a double)");
  }
  if (!root.is_object()) throw std::invalid_argument(source + ": plan.json must be one JSON object");
  // Files without the field predate it (schema 1); a newer schema may have changed what a key means.
  if (root.contains("schema_version") && r.Number(root, "schema_version", "") > kSchemaVersion) {
    r.Fail("schema_version", "the file has schema " + root["schema_version"].dump() + ", newer than this stairplan " + kVersion +
                                 " reads (" + std::to_string(kSchemaVersion) + "); update stairplan");
  }
  PlanFile file;
  Plan& plan = file.plan;
  const json& robot = r.At(root, "robot", "");
  plan.robot_name = r.Text(robot, "name", "robot.");
  plan.robot_source = robot.contains("source") ? r.Text(robot, "source", "robot.") : std::string();
  const json& legs = r.Array(robot, "legs", "robot.");
  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!legs[i].is_string()) r.Fail("robot.legs[" + std::to_string(i) + "]", "must be a string");
    plan.legs.push_back(legs[i].get<std::string>());
  }
  if (plan.legs.size() != 4) r.Fail("robot.legs", "must name 4 legs");
  file.stairs = ReadStairs(r, r.At(root, "stairs", ""));
  const std::string facing = root.contains("facing") ? r.Text(root, "facing", "") : "forward";
  if (facing != "forward" && facing != "backward") r.Fail("facing", "must be 'forward' or 'backward'");
  file.facing = facing == "forward" ? Facing::kForward : Facing::kBackward;
  plan.facing = file.facing;
  // Files from before the gait was written walked the crawl; an empty name: no controller chosen.
  const std::string gait = root.contains("gait") ? r.Text(root, "gait", "") : ToString(Gait::kCrawl);
  if (!gait.empty()) {
    plan.gait = ParseGait(gait);
    if (!plan.gait) {
      std::string names;
      for (const Gait g : kAllGaits) names += (names.empty() ? "" : ", ") + std::string(ToString(g));
      r.Fail("gait", "must be one of " + names + " (got '" + gait + "')");
    }
  }
  plan.cadence_s = r.Number(root, "cadence_s", "");
  if (root.contains("hip_height_fraction") && !root["hip_height_fraction"].is_null()) {
    plan.hip_height_fraction = r.Number(root, "hip_height_fraction", "");
    if (plan.hip_height_fraction <= 0.0 || plan.hip_height_fraction > 1.0) r.Fail("hip_height_fraction", "must be in (0, 1]");
  }
  if (root.contains("body_planner")) {
    const std::string kind = r.Text(root, "body_planner", "");
    bool known = false;
    for (const BodyPlannerKind k : {BodyPlannerKind::kQuasiStaticPath, BodyPlannerKind::kRecedingHorizonQp,
                                    BodyPlannerKind::kRecedingHorizonNlp}) {
      if (kind == ToString(k)) plan.body_planner = k, known = true;
    }
    if (!known) r.Fail("body_planner", "must be quasi_static_path, receding_horizon_qp or receding_horizon_nlp");
  }
  const std::string status = r.Text(root, "status", "");
  plan.status = status == "ok" ? PlanStatus::kOk : PlanStatus::kInfeasible;
  const json& initial = r.Array(root, "initial_feet", "");
  if (initial.size() != 4) r.Fail("initial_feet", "must hold 4 feet");
  for (std::size_t i = 0; i < initial.size(); ++i) plan.initial_feet_W.push_back(r.Point(initial[i], "initial_feet[" + std::to_string(i) + "]."));
  const json& steps = r.Array(root, "footsteps", "");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::string path = "footsteps[" + std::to_string(i) + "].";
    plan.footsteps.push_back(ReadFootstep(r, steps[i], path));
    if (std::find(plan.legs.begin(), plan.legs.end(), plan.footsteps.back().leg) == plan.legs.end()) r.Fail(path + "leg", "names no leg of the robot");
  }
  const json& body = r.Array(root, "body", "");
  if (body.empty()) r.Fail("body", "must not be empty");
  for (std::size_t i = 0; i < body.size(); ++i) {
    plan.body.push_back(ReadBody(r, body[i], "body[" + std::to_string(i) + "]."));
    if (i > 0 && plan.body[i].t < plan.body[i - 1].t) r.Fail("body[" + std::to_string(i) + "].t", "times must not decrease");
  }
  LinkFootholds(plan);
  return file;
}

PlanFile ReadPlanJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open the plan file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ReadPlanJson(buffer.str(), path);
}

}  // namespace stairplan
