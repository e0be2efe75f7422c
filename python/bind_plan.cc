// Planning, validation, simulation and the gait design: stairplan.plan() over the pipeline (through
// pipeline_adapter.h), the Plan with numpy footsteps and body, validate(),
// simulate(), design_gait().
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "stairplan/geometry/field_error.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "pipeline_adapter.h"
#include "stairplan/planning/gait/gait_design.h"
#include "stairplan/planning/plan_json.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/planning/plan_svg.h"
#include "stairplan/simulation/plan_executor.h"
#include "stairplan/simulation/sim_outcome_json.h"
#include "stairplan/planning/stair_approach_json.h"

namespace stairplan::python {
namespace {

template <typename T, typename F>
py::array_t<T> Column(const std::vector<Footstep>& steps, F get) {
  py::array_t<T> out(static_cast<py::ssize_t>(steps.size()));
  auto a = out.template mutable_unchecked<1>();
  for (std::size_t i = 0; i < steps.size(); ++i) a(static_cast<py::ssize_t>(i)) = get(steps[i]);
  return out;
}

py::object Footsteps(const Plan& plan) {
  const auto& f = plan.footsteps;
  py::list legs;
  for (const Footstep& s : f) legs.append(s.leg);
  const py::object numpy = py::module_::import("numpy");
  return StructuredArray({
      {"leg", numpy.attr("array")(legs, py::arg("dtype") = "U4")},
      {"t_liftoff", Column<double>(f, [](const Footstep& s) { return s.t_liftoff; })},
      {"t_touchdown", Column<double>(f, [](const Footstep& s) { return s.t_touchdown; })},
      {"x", Column<double>(f, [](const Footstep& s) { return s.position_W.x(); })},
      {"y", Column<double>(f, [](const Footstep& s) { return s.position_W.y(); })},
      {"z", Column<double>(f, [](const Footstep& s) { return s.position_W.z(); })},
      {"stair_index", Column<std::int32_t>(f, [](const Footstep& s) { return s.stair_index; })},
      {"in_step_region", Column<bool>(f, [](const Footstep& s) { return s.in_step_region; })},
  });
}

py::object Body(const std::vector<BodyState>& body) {
  std::vector<std::pair<std::string, py::object>> columns;
  const std::pair<const char*, double BodyState::*> fields[] = {
      {"t", &BodyState::t}, {"x", &BodyState::x}, {"y", &BodyState::y}, {"z", &BodyState::z},
      {"pitch", &BodyState::pitch}, {"yaw", &BodyState::yaw}, {"com_shift", &BodyState::com_shift},
      {"com_shift_y", &BodyState::com_shift_y}};
  for (const auto& [name, member] : fields) {
    py::array_t<double> column(static_cast<py::ssize_t>(body.size()));
    auto a = column.mutable_unchecked<1>();
    for (std::size_t i = 0; i < body.size(); ++i) a(static_cast<py::ssize_t>(i)) = body[i].*member;
    columns.emplace_back(name, std::move(column));
  }
  return StructuredArray(columns);
}

PlanResult RunPlan(const py::object& robot_arg, const py::object& stairs_arg, const py::kwargs& kwargs) {
  nlohmann::json options = nlohmann::json::object(), stair_fields = nlohmann::json::object(), start;
  const nlohmann::json given = FromPython(kwargs, "");
  for (const auto& [key, value] : given.items()) {
    const auto& names = StairOptionNames();
    if (value.is_null()) continue;
    if (key == "start") {
      start = value;  // plan()'s alone: where the robot stands before these stairs
      continue;
    }
    (std::find(names.begin(), names.end(), key) != names.end() ? stair_fields : options)[key] = value;
  }
  PipelineOptions pipeline = PipelineOptionsFrom(options);
  PlanResult out;
  out.robot = std::make_shared<RobotModel>(RobotArg(robot_arg));
  const Perceived* perceived = py::isinstance<Perceived>(stairs_arg) ? &stairs_arg.cast<const Perceived&>() : nullptr;
  if (perceived != nullptr && !perceived->found) throw FieldError("stairs", "no stairs were perceived: " + perceived->reason);
  if (perceived != nullptr && !stair_fields.empty()) {
    throw FieldError(stair_fields.begin().key(), "stair fields do not apply to perceived stairs");
  }
  out.stairs = perceived ? perceived->stairs : std::make_shared<Staircase>(StairsArg(stairs_arg, stair_fields));
  const StairFrame* world = perceived ? perceived->frame.get() : nullptr;
  SetRobotStart(start, world, pipeline);
  auto result = std::make_shared<PipelineResult>();
  {
    py::gil_scoped_release release;
    *result = RunPlanPipeline(*out.robot, *out.stairs, perceived ? perceived->map.get() : nullptr, pipeline);
    out.json = PlanToJson(result->plan, *out.stairs, result->map);
    if (result->validated) out.json["validation"] = ValidationToJson(result->validation);
    out.json["clearance"] = ClearancesToJson(result->clearances);
    // As `stairplan plan` writes them: the robot's pose and its source, in the cloud's world too.
    out.json.update(StairApproachToJson(result->approach, result->plan, world));
  }
  if (perceived != nullptr) out.json["fitted"] = FromPython(perceived->fit, "fit");
  out.result = std::move(result);
  return out;
}

const Plan& PlanOf(const PlanResult& p) { return p.result->plan; }

void BindPlanClass(py::module_& m) {
  py::class_<PlanResult>(m, "Plan", R"(A planned traversal (stairplan.plan()).

`footsteps` and `body` are numpy structured arrays; to_dict() equals the plan.json that
`stairplan plan` writes for the same inputs (its timing_us aside).)")
      .def_property_readonly("status", [](const PlanResult& p) { return std::string(ToString(PlanOf(p).status)); },
                             "'ok' or 'infeasible'.")
      .def_property_readonly("status_reason", [](const PlanResult& p) { return PlanOf(p).status_reason; })
      .def_property_readonly("validated", [](const PlanResult& p) { return p.result->validated; })
      .def_property_readonly("valid", [](const PlanResult& p) { return p.result->validated && p.result->validation.ok; },
                             "The validator found no violation (False when not validated).")
      .def_property_readonly("ok", [](const PlanResult& p) {
        return PlanOf(p).status == PlanStatus::kOk && (!p.result->validated || p.result->validation.ok);
      }, "Planned, and valid when validated: what makes the CLI exit 0.")
      .def_property_readonly("gait", [](const PlanResult& p) { return GaitName(PlanOf(p).gait); })
      .def_property_readonly("cadence_s", [](const PlanResult& p) { return PlanOf(p).cadence_s; })
      .def_property_readonly("duration", [](const PlanResult& p) { return PlanOf(p).duration(); })
      .def_property_readonly("legs", [](const PlanResult& p) { return PlanOf(p).legs; })
      .def_property_readonly("footsteps", [](const PlanResult& p) { return Footsteps(PlanOf(p)); },
                             "Structured array: leg, t_liftoff, t_touchdown, x, y, z, stair_index, in_step_region.")
      .def_property_readonly("body", [](const PlanResult& p) { return Body(PlanOf(p).body); },
                             "Structured array: t, x, y, z, pitch, yaw, com_shift, com_shift_y.")
      .def_property_readonly("validation", [](const PlanResult& p) {
        return p.result->validated ? ToPython(p.json.at("validation")) : py::none();
      }, "The validator's report as plan.json's `validation` dict, or None.")
      .def_property_readonly("timing_us", [](const PlanResult& p) {
        py::dict out;
        for (const auto& [stage, us] : PlanOf(p).timing_us) out[py::str(stage)] = us;
        return out;
      })
      .def_property_readonly("robot", [](const PlanResult& p) { return std::const_pointer_cast<RobotModel>(p.robot); })
      .def_property_readonly("stairs", [](const PlanResult& p) { return std::const_pointer_cast<Staircase>(p.stairs); })
      .def_property_readonly("map", [](const PlanResult& p) {
        return std::make_shared<ConstrainedMap>(p.result->map);
      }, "The constrained map it was planned on.")
      .def("to_dict", [](const PlanResult& p) { return ToPython(p.json); }, "plan.json as a dict.")
      .def("to_json", [](const PlanResult& p) { return p.json.dump(2) + "\n"; }, "plan.json's text.")
      .def("to_svg", [](const PlanResult& p) { return PlanToSvg(PlanOf(p), *p.stairs, p.result->map); },
           "plan.svg's text: the stairs, the regions, the footsteps and the body.")
      .def("__repr__", [](const PlanResult& p) {
        return "<stairplan.Plan " + std::string(ToString(PlanOf(p).status)) + ", " +
               std::to_string(PlanOf(p).footsteps.size()) + " footsteps, " + std::to_string(PlanOf(p).duration()) + " s>";
      });
}

// The robot a plan.json names: the built-in robot or its URDF path.
RobotModel PlanFileRobot(const Plan& plan) {
  const std::string& source = plan.robot_source;
  if (source.empty() || source.rfind("builtin:", 0) == 0) return BuiltinRobot();
  RequireFile(source);
  return RobotModel::FromUrdfFile(source);
}

py::object Validate(const py::object& plan_arg, const py::object& robot_arg) {
  nlohmann::json report;
  if (py::isinstance<PlanResult>(plan_arg)) {
    const PlanResult& p = plan_arg.cast<const PlanResult&>();
    const RobotModel robot = robot_arg.is_none() ? *p.robot : RobotArg(robot_arg);
    py::gil_scoped_release release;
    const PipelineOptions options = OptionsForPlan(PlanOf(p));
    TraversalValidator validator(robot, *p.stairs, p.result->map, options.validation);
    report = ValidationToJson(validator.Validate(PlanOf(p)));
  } else {
    const std::string path = PathArg(plan_arg, "plan");
    RequireFile(path);
    const PlanFile file = ReadPlanJsonFile(path);
    const RobotModel robot = robot_arg.is_none() ? PlanFileRobot(file.plan) : RobotArg(robot_arg);
    const Staircase stairs(file.stairs);
    py::gil_scoped_release release;
    const PipelineOptions options = OptionsForPlan(file.plan);
    const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
    TraversalValidator validator(robot, stairs, map, options.validation);
    report = ValidationToJson(validator.Validate(file.plan));
  }
  return ToPython(report);
}

py::object SimulatePlan(const PlanResult& p, const py::object& settings_arg, const py::kwargs& kwargs) {
  SimSettings settings;
  const auto apply = [&](const py::handle& fields) {
    for (const auto& [key, value] : fields.cast<py::dict>()) {
      const std::string name = py::str(key);
      if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value)) {
        throw FieldError(name, "must be a number");
      }
      settings.Set(name, value.cast<double>());
    }
  };
  if (!settings_arg.is_none()) apply(settings_arg);
  apply(kwargs);
  settings.Validate();
  SimulationOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = Simulate(*p.robot, *p.stairs, PlanOf(p), settings);
  }
  return ToPython(SimulationToJson(outcome));
}

py::dict GaitDesignDict(const GaitDesign& d) {
  py::dict out;
  const std::pair<const char*, double> numbers[] = {{"cl", d.cl},       {"phi", d.phi}, {"l_min", d.l_min},
                                                    {"d", d.d},         {"a_min", d.a_min}, {"a_max", d.a_max},
                                                    {"d_s", d.d_s},     {"d_i", d.d_i}, {"d_o", d.d_o},
                                                    {"rem", d.rem}};
  for (const auto& [name, value] : numbers) out[name] = value;
  py::list conditions;
  for (const GaitCondition& c : d.conditions) {
    conditions.append(py::dict(py::arg("name") = c.name, py::arg("text") = c.text, py::arg("holds") = c.holds,
                               py::arg("slack") = c.slack));
  }
  out["conditions"] = conditions;
  out["feasible"] = d.feasible;
  out["binding"] = d.binding;
  return out;
}

}  // namespace

void BindPlan(py::module_& m) {
  BindPlanClass(m);
  m.def("plan", &RunPlan, py::arg("robot") = py::none(), py::arg("stairs") = py::none(),
        R"(Plans, and validates, a traversal: the pipeline `stairplan plan` runs, with its defaults.

robot:   None (the built-in stairbot), a Robot or a URDF path.
stairs:  None (7 steps, rise 0.17, run 0.27), a Stairs, a dict of stairs YAML keys, a YAML
         path, or a Perception (stairplan.perceive) to plan on its map.
options: the CLI's flags as keywords -- steps, rise, run, nosing, width, direction ('up' or
         'down') override the stairs' fields; facing ('forward' or 'backward'), planner
         ('crawl' or 'step'), gait ('crawl', the default, 'walk', 'trot' or 'auto': the
         fastest of the trot, the walk and the crawl whose plan validates), crawl_sequence ('lateral', 'leading-first' or 'pairs'), body ('qp', the default, or
         'path', the quasi-static baseline), horizon (knots, implies body='qp'), nlp
         ('ipopt' or 'nlopt', implies body='qp'), validate (True), validation_time_step (0.02 s),
         start ((x, y, yaw): the robot's pose, where stair mode is judged; in the cloud's world for
         a Perception, else in the stairs' frame; default: at the alignment pose).

Returns a Plan (status 'infeasible' with a reason when there is no plan; no exception).
Raises ValueError (stairplan.FieldError, `.field` names it) for a bad option or stair field,
FileNotFoundError for a missing file. Releases the GIL while planning.)");
  m.def("validate", &Validate, py::arg("plan"), py::arg("robot") = py::none(),
        R"(Replays a Plan or a plan.json file through the validator (IK, joint limits, clearances,
stability, step regions, body acceleration, dynamics), as `stairplan validate`. Returns the report
dict: ok, min_clearance_m, min_stability_margin_m, samples, dynamics {mode,
torque_limits_checked, body_inertia_known, friction, tolerance_n, max_residual_n, max_residual_t,
failed_instants, first_failure {t, kind, leg} when one fails}, violations [{t, leg, kind, family,
value, detail}].)");
  m.def("simulate", &SimulatePlan, py::arg("plan"), py::arg("settings") = py::none(),
        R"(Executes a Plan in MuJoCo, as `stairplan simulate`; returns the outcome dict (success,
cause, landings, contacts, peak torques, slip, ...). Numeric simulation settings by name, as
keywords or in `settings` (e.g. {"world.friction": 0.8, "time_scale": 2}); ValueError names an
unknown or bad one. Releases the GIL.)");
  m.def("design_gait", [](double rise, double run, double max_leg_length, double body_length, double body_width,
                          double buffer, std::optional<double> hip_clearance) {
    GaitDesignInput input;
    input.rise = rise;
    input.run = run;
    input.max_leg_length = max_leg_length;
    input.body_length = body_length;
    input.body_width = body_width;
    input.buffer = buffer;
    input.hip_clearance = hip_clearance;
    return GaitDesignDict(DesignGait(input));
  }, py::arg("rise") = 0.17, py::arg("run") = 0.27, py::arg("max_leg_length") = 0.21, py::arg("body_length") = 0.444,
        py::arg("body_width") = 0.36, py::arg("buffer") = 0.42, py::arg("hip_clearance") = py::none(),
        R"(The 2012 paper's crawl design (Chen et al., "Stair Climbing in a Quadruped Robot") for one
staircase: cl, phi, l_min, d, a_min, a_max, d_s, d_i, d_o, rem [m, rad], the conditions
[{name, text, holds, slack}], feasible and the binding condition. ValueError for bad input.)");
}

}  // namespace stairplan::python
