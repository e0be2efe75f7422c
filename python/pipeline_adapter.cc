#include "pipeline_adapter.h"

#include <cmath>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "stairplan/sweep/pipeline_sweep_row.h"

namespace stairplan::python {
namespace {

std::string Text(const nlohmann::json& value, const std::string& name) {
  if (!value.is_string()) throw FieldError(name, "must be a string (got " + value.dump() + ")");
  return value.get<std::string>();
}

std::string OneOf(const nlohmann::json& value, const std::string& name, const std::vector<std::string>& choices) {
  const std::string text = Text(value, name);
  for (const std::string& c : choices) {
    if (c == text) return text;
  }
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "'" : ", '") + c + "'";
  throw FieldError(name, "must be one of " + list + " (got '" + text + "')");
}

// The CLI's --body/--horizon/--nlp rule: a horizon or an NLP implies the body QP.
void SetBody(const nlohmann::json& o, PipelineOptions& options) {
  const auto given = [&](const char* key) { return o.contains(key) && !o.at(key).is_null(); };
  const std::string body = given("body") ? OneOf(o.at("body"), "body", {"path", "qp"}) : "";
  bool qp = body == "qp";
  if (given("horizon")) {
    const nlohmann::json& h = o.at("horizon");
    if (!h.is_number_integer() || h.get<int>() < 4 || h.get<int>() > 400) {
      throw FieldError("horizon", "must be a whole number of knots from 4 to 400 (got " + h.dump() + ")");
    }
    options.body_qp.knots = h.get<int>();
    qp = true;
  }
  if (given("nlp")) {
    options.body_nlp = OneOf(o.at("nlp"), "nlp", {"ipopt", "nlopt"});
    qp = true;
  }
  if (qp) options.body = BodySource::kRecedingHorizonQp;
  if (body == "path") options.body = BodySource::kQuasiStaticPath;
}

}  // namespace

const std::vector<std::string>& StairOptionNames() {
  static const std::vector<std::string> names = {"steps", "rise", "run", "nosing", "width", "direction"};
  return names;
}

PipelineOptions PipelineOptionsFrom(const nlohmann::json& o) {
  static const std::vector<std::string> known = {"facing", "planner", "gait", "crawl_sequence", "body", "horizon",
                                                 "nlp", "validate", "validation_time_step"};
  for (const auto& [key, value] : o.items()) {
    bool found = false;
    for (const std::string& k : known) found = found || k == key;
    if (!found) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw FieldError(key, "unknown option (known: " + list + ")");
    }
  }
  PipelineOptions options;
  if (o.contains("facing") && !o.at("facing").is_null()) {
    options.facing = OneOf(o.at("facing"), "facing", {"forward", "backward"}) == "forward" ? Facing::kForward
                                                                                          : Facing::kBackward;
  }
  if (o.contains("planner") && !o.at("planner").is_null()) {
    options.footsteps = ParseFootstepSource(OneOf(o.at("planner"), "planner", {"crawl", "step"}));
  }
  if (o.contains("gait") && !o.at("gait").is_null()) {
    options.gait = ParseGaitChoice(OneOf(o.at("gait"), "gait", {"crawl", "walk", "trot", "auto"}));
  }
  if (o.contains("crawl_sequence") && !o.at("crawl_sequence").is_null()) {
    options.crawl.sequence = ParseCrawlSequence(OneOf(o.at("crawl_sequence"), "crawl_sequence", {"lateral", "leading-first", "pairs"}));
  }
  SetBody(o, options);
  if (o.contains("validate") && !o.at("validate").is_null()) {
    if (!o.at("validate").is_boolean()) throw FieldError("validate", "must be True or False");
    options.validate = o.at("validate").get<bool>();
  }
  if (o.contains("validation_time_step") && !o.at("validation_time_step").is_null()) {
    const nlohmann::json& v = o.at("validation_time_step");
    RequireInRange("validation_time_step", v.is_number() ? v.get<double>() : NAN, 1e-4, 1.0);
    options.validation.time_step = v.get<double>();
  }
  return options;
}

void SetRobotStart(const nlohmann::json& start, const StairFrame* world, PipelineOptions& options) {
  if (start.is_null()) return;
  std::vector<double> xy_yaw;
  if (start.is_array()) {
    for (const nlohmann::json& v : start) xy_yaw.push_back(v.is_number() ? v.get<double>() : NAN);
  }
  try {
    options.robot_pose = RobotPoseInPlanFrame(xy_yaw, world);
  } catch (const std::invalid_argument& e) {
    throw FieldError("start", std::string(e.what()) + " (got " + start.dump() + ")");
  }
  options.robot_pose_source = RobotPoseSource::kGiven;
}

StairSpec StairSpecFrom(const nlohmann::json& fields, const std::string& source) {
  // A JSON object is YAML flow syntax: the stairs YAML reader checks the keys and values.
  return StairSpecFromYaml(fields.dump(), source);
}

Staircase StairsFrom(StairSpec base, const nlohmann::json& overrides, const std::string& source) {
  if (overrides.empty()) return Staircase(base);
  const bool steps = overrides.contains("steps");
  if ((overrides.contains("rise") || steps) && !overrides.contains("rises")) base.rises.clear();
  if ((overrides.contains("run") || steps) && !overrides.contains("runs")) base.runs.clear();
  return Staircase(StairSpecFromYaml(overrides.dump(), source, base));
}

PipelineResult RunPlanPipeline(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap* perceived_map,
                               const PipelineOptions& options) {
  if (perceived_map == nullptr) return RunPipeline(robot, stairs, options);
  ConstrainedMap map = *perceived_map;
  AddPipelineRobotRegions(robot, stairs, options, map);
  return RunPipelineOnMap(robot, stairs, map, options);
}

SweepRow EvaluateSweepPoint(const SweepPoint& point, const RobotModel& robot, const PipelineOptions& options) {
  try {
    return PipelineSweepRow(point, RunPipeline(robot, Staircase(point.Spec()), options));
  } catch (const std::invalid_argument& e) {
    SweepRow row;
    row.point = point;
    row.status = "bad_stairs";
    row.reason = e.what();
    return row;
  }
}

}  // namespace stairplan::python
