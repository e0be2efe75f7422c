#include "stairplan/viewer/viewer_scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/planning/json_field_reader.h"
#include "stairplan/planning/swing_trajectory.h"
#include "stairplan/viewer/viewer_robot.h"

namespace stairplan {
namespace {

using nlohmann::json;

// Millimetre-and-better rounding keeps the page small; nothing drawn needs more.
double Rounded(double v) { return std::round(v * 1e4) / 1e4; }
json RoundedVec(const Eigen::Vector3d& v) { return {Rounded(v.x()), Rounded(v.y()), Rounded(v.z())}; }

// One frame of poses, flattened: x y z qx qy qz qw per shape.
void AppendPoses(const std::vector<Eigen::Isometry3d>& poses, json* flat) {
  for (const Eigen::Isometry3d& p : poses) {
    const Eigen::Quaterniond q(p.linear());
    for (double v : {p.translation().x(), p.translation().y(), p.translation().z(), q.x(), q.y(), q.z(), q.w()}) {
      flat->push_back(Rounded(v));
    }
  }
}

json StairSolids(const Staircase& stairs) {
  json solids = json::array();
  for (const Box3& b : stairs.Solids()) {
    solids.push_back({{"min", RoundedVec(b.min)}, {"max", RoundedVec(b.max)}, {"nosing", b.kind == SolidKind::kNosing}});
  }
  return solids;
}

json Polygon(const JsonFieldReader& r, const json& node, const std::string& key, const std::string& path) {
  json out = json::array();
  const json& points = r.Array(node, key, path);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const json& p = points[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
        !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>())) {
      r.Fail(path + key + "[" + std::to_string(i) + "]", "must be [x, y] of finite numbers");
    }
    out.push_back({Rounded(p[0].get<double>()), Rounded(p[1].get<double>())});
  }
  return out;
}

// plan.json's map as written (the regions the plan was made on); none when it has no map.
json MapRegions(const JsonFieldReader& r, const json& plan_json) {
  json regions = json::array();
  if (!plan_json.contains("map")) return regions;
  const json& stairs = r.Array(r.At(plan_json, "map", ""), "stairs", "map.");
  for (std::size_t i = 0; i < stairs.size(); ++i) {
    const std::string p = "map.stairs[" + std::to_string(i) + "].";
    json collisions = json::array();
    const json& list = r.Array(stairs[i], "collision_regions", p);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string pk = p + "collision_regions[" + std::to_string(k) + "].";
      collisions.push_back({{"kind", r.Text(list[k], "kind", pk)}, {"polygon", Polygon(r, list[k], "polygon", pk)}});
    }
    regions.push_back({{"z", Rounded(r.Number(stairs[i], "z", p))},
                       {"step", Polygon(r, stairs[i], "step_region", p)},
                       {"collision", collisions}});
  }
  return regions;
}

json Footsteps(const Plan& plan) {
  json steps = json::array();
  for (std::size_t i = 0; i < plan.initial_feet_W.size() && i < plan.legs.size(); ++i) {
    steps.push_back({{"leg", plan.legs[i]}, {"t", 0.0}, {"p", RoundedVec(plan.initial_feet_W[i])}, {"ok", true}, {"initial", true}});
  }
  for (const Footstep& f : plan.footsteps) {
    steps.push_back({{"leg", f.leg},
                     {"t", Rounded(f.t_touchdown)},
                     {"t_liftoff", Rounded(f.t_liftoff)},
                     {"p", RoundedVec(f.position_W)},
                     {"ok", f.in_step_region},
                     {"initial", false}});
  }
  return steps;
}

// Poses the plan's robot over time and answers where things are at a given instant.
class PlanReplay {
 public:
  PlanReplay(ViewerRobot& robot, const Plan& plan, const Staircase& stairs) : robot_(robot), plan_(plan), stairs_(stairs) {}

  // The feet's contact points at t in kinematics leg order.
  std::array<Eigen::Vector3d, 4> Contacts(double t) const {
    const std::vector<Eigen::Vector3d> feet =
        FeetAlongSwings(plan_.legs, plan_.initial_feet_W, plan_.footsteps, t, stairs_, SwingSettings{});
    std::array<Eigen::Vector3d, 4> contacts;
    contacts.fill(Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < plan_.legs.size() && i < feet.size(); ++i) {
      const int l = robot_.kinematics().LegIndex(plan_.legs[i]);
      if (l >= 0 && l < 4) contacts[static_cast<std::size_t>(l)] = feet[i];
    }
    return contacts;
  }
  const std::vector<Eigen::Isometry3d>& Poses(double t) {
    const BodyPose body = BodyPoseAt(plan_.body, t);
    robot_.ShapePoses(body, robot_.PlanAngles(body, Contacts(t)), &poses_);
    return poses_;
  }

 private:
  ViewerRobot& robot_;
  const Plan& plan_;
  const Staircase& stairs_;
  std::vector<Eigen::Isometry3d> poses_;
};

json PlanFrames(PlanReplay& replay, const Plan& plan, double period) {
  json times = json::array();
  json poses = json::array();
  const double duration = plan.duration();
  const int count = static_cast<int>(std::ceil(duration / period - 1e-9));
  for (int k = 0; k <= count; ++k) {
    const double t = std::min(k * period, duration);
    times.push_back(Rounded(t));
    AppendPoses(replay.Poses(t), &poses);
  }
  return {{"t", times}, {"poses", poses}};
}

// Where a violation happened: the offending link when the validator names it, the footstep for a
// touchdown outside its region, the leg's foot, both legs of a pair, or the body.
Eigen::Vector3d ViolationPlace(PlanReplay& replay, const ViewerRobot& robot, const Plan& plan, double when,
                               const std::string& leg, const std::string& kind, const std::string& detail) {
  if (kind == "foot_outside_step_region") {
    for (const Footstep& f : plan.footsteps) {
      if (f.leg == leg && std::abs(f.t_touchdown - when) < 1e-6) return f.position_W;
    }
  }
  const double t = std::clamp(when, 0.0, plan.duration());
  const std::vector<Eigen::Isometry3d>& poses = replay.Poses(t);
  const std::vector<ViewerShape>& shapes = robot.shapes();
  const std::string link = detail.substr(0, detail.find(" against "));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  const auto add_if = [&](const auto& keep) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      if (keep(shapes[i])) {
        sum += poses[i].translation();
        ++n;
      }
    }
  };
  add_if([&](const ViewerShape& s) { return !link.empty() && s.link == link; });
  const std::size_t slash = leg.find('/');
  if (n == 0 && slash != std::string::npos) {
    add_if([&](const ViewerShape& s) { return s.group == leg.substr(0, slash) || s.group == leg.substr(slash + 1); });
  }
  if (n > 0) return sum / n;
  const std::array<Eigen::Vector3d, 4> contacts = replay.Contacts(t);
  for (int l = 0; l < robot.kinematics().leg_count() && l < 4; ++l) {
    if (robot.kinematics().leg(l).name() == leg) return contacts[static_cast<std::size_t>(l)];
  }
  return BodyPoseAt(plan.body, t).position_W;
}

// The validator's report: {ok, violations [{t, leg, kind, value, detail}]}; `path` prefixes its fields.
json Violations(const JsonFieldReader& r, const json& report, const std::string& path, PlanReplay& replay,
                const ViewerRobot& robot, const Plan& plan) {
  json out = json::array();
  const json& list = r.Array(report, "violations", path);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string p = path + "violations[" + std::to_string(i) + "].";
    const double t = r.Number(list[i], "t", p);
    const std::string leg = r.Text(list[i], "leg", p);
    const std::string kind = r.Text(list[i], "kind", p);
    const std::string detail = list[i].contains("detail") ? r.Text(list[i], "detail", p) : "";
    const double value = r.Number(list[i], "value", p);
    out.push_back({{"t", Rounded(t)},
                   {"leg", leg},
                   {"kind", kind},
                   {"value", value},
                   {"detail", detail},
                   {"p", RoundedVec(ViolationPlace(replay, robot, plan, t, leg, kind, detail))}});
  }
  return out;
}

// The run's impacts and responses (seed 000 [0053]-[0068]) where they happened: the foot (or for
// a touchdown, where it landed) and the swing's target after the response. Outputs from before
// impacts were recorded have none; those from before their places were recorded are refused.
json SimImpacts(const JsonFieldReader& r, const json& sim) {
  json out = json::array();
  if (!sim.contains("impacts")) return out;
  const json& list = r.Array(sim, "impacts", "");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string p = "impacts[" + std::to_string(i) + "].";
    const json& executed = r.At(list[i], "executed", p);
    if (!executed.is_boolean()) r.Fail(p + "executed", "must be true or false");
    out.push_back({{"t", Rounded(r.Number(list[i], "t", p))},
                   {"leg", r.Text(list[i], "leg", p)},
                   {"kind", r.Text(list[i], "kind", p)},
                   {"response", r.Text(list[i], "response", p)},
                   {"executed", executed.get<bool>()},
                   {"reason", r.Text(list[i], "reason", p)},
                   {"p", RoundedVec(r.Triple(list[i], "at", p))},
                   {"target", RoundedVec(r.Triple(list[i], "target", p))}});
  }
  return out;
}

// The simulated robot: each recorded base pose and joint angles posed through the same shapes.
json SimFrames(ViewerRobot& robot, const json& sim, const std::string& source) {
  const JsonFieldReader r(source);
  const json& frames = r.Array(sim, "frames", "");
  if (frames.empty()) r.Fail("frames", "is empty: run `stairplan simulate` with --frame-ms");
  json times = json::array();
  json poses = json::array();
  std::vector<Eigen::Isometry3d> shape_poses;
  const RobotKinematics& kinematics = robot.kinematics();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string p = "frames[" + std::to_string(i) + "].";
    BodyPose body;
    body.position_W = r.Triple(frames[i], "base", p);
    const Eigen::Vector3d rpy = r.Triple(frames[i], "roll_pitch_yaw", p);
    body.roll = rpy.x();
    body.pitch = rpy.y();
    body.yaw = rpy.z();
    LegAngles q;
    for (int l = 0; l < kinematics.leg_count() && l < 4; ++l) {
      q[static_cast<std::size_t>(l)] = r.Triple(r.At(frames[i], "q", p), kinematics.leg(l).name(), p + "q.");
    }
    robot.ShapePoses(body, q, &shape_poses);
    times.push_back(Rounded(r.Number(frames[i], "t", p)));
    AppendPoses(shape_poses, &poses);
  }
  json out = {{"t", times}, {"poses", poses}};
  out["impacts"] = SimImpacts(r, sim);
  out["status"] = sim.contains("status") ? r.Text(sim, "status", "") : "";
  out["cause"] = sim.contains("first_cause") ? r.Text(sim, "first_cause", "") : "";
  return out;
}

std::string Title(const Plan& plan, const StairSpec& spec, bool valid, const json& violations) {
  std::ostringstream title;
  title << plan.robot_name << ", " << spec.steps << " steps (rise " << spec.rise << " m, run " << spec.run << " m, "
        << ToString(spec.direction) << "), " << GaitName(plan.gait) << ": ";
  if (valid) {
    title << "valid";
  } else if (!violations.empty()) {
    const json& v = violations.front();
    title << "INVALID: " << v["kind"].get<std::string>() << " (" << v["leg"].get<std::string>() << ") at t = "
          << v["t"].get<double>() << " s";
  } else {
    title << "INVALID: " << (plan.status_reason.empty() ? ToString(plan.status) : plan.status_reason);
  }
  return title.str();
}

}  // namespace

void ViewerSceneSettings::Validate() const { RequireInRange("frame_period", frame_period, 1e-3, 1.0); }

json BuildViewerScene(const RobotModel& robot, const PlanFile& plan_file, const JsonSource& plan_source,
                      const JsonSource& validation, const JsonSource& sim, const ViewerSceneSettings& settings) {
  settings.Validate();
  if (plan_source.json == nullptr) throw std::invalid_argument("BuildViewerScene: no plan.json given");
  const json& plan_json = *plan_source.json;
  const Plan& plan = plan_file.plan;
  const JsonFieldReader r(plan_source.name);
  const Staircase stairs(plan_file.stairs);
  ViewerRobot viewer_robot(robot, stairs);
  PlanReplay replay(viewer_robot, plan, stairs);

  json shapes = json::array();
  for (const ViewerShape& s : viewer_robot.shapes()) {
    shapes.push_back({{"type", ToString(s.type)}, {"size", RoundedVec(s.size)}, {"link", s.link}, {"group", s.group}});
  }
  json scene;
  scene["robot"] = {{"name", plan.robot_name}, {"legs", plan.legs}, {"shapes", shapes}};
  scene["duration"] = plan.duration();
  scene["stairs"] = StairSolids(stairs);
  scene["regions"] = MapRegions(r, plan_json);
  scene["footsteps"] = Footsteps(plan);
  json body = json::array();
  for (const BodyState& b : plan.body) body.push_back({Rounded(b.t), Rounded(b.x), Rounded(b.y), Rounded(b.z)});
  scene["body"] = body;
  scene["frames"] = PlanFrames(replay, plan, settings.frame_period);
  // The report drawn: the one given, else plan.json's own; none when neither exists.
  bool valid = plan.status == PlanStatus::kOk;
  scene["violations"] = json::array();
  const bool own = validation.json == nullptr;
  if (!own || plan_json.contains("validation")) {
    const JsonFieldReader rv(own ? plan_source.name : validation.name);
    const json& report = own ? plan_json.at("validation") : *validation.json;
    const std::string path = own ? "validation." : "";
    scene["violations"] = Violations(rv, report, path, replay, viewer_robot, plan);
    const json& ok = rv.At(report, "ok", path);
    if (!ok.is_boolean()) rv.Fail(path + "ok", "must be true or false");
    valid = valid && ok.get<bool>();
  }
  valid = valid && scene["violations"].empty();
  scene["valid"] = valid;
  scene["title"] = Title(plan, plan_file.stairs, valid, scene["violations"]);
  scene["sim"] = sim.json != nullptr ? SimFrames(viewer_robot, *sim.json, sim.name) : json(nullptr);
  return scene;
}

}  // namespace stairplan
