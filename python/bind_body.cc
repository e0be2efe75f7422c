// The body planner's control-loop API for a Python loop: BodyPlanner.update() once per cycle
// (e.g. at 333 Hz). update() returns the planner's own output object, not a copy, so a call
// costs the C++ Update plus the binding's argument conversion.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/pipeline/plan_pipeline.h"

namespace stairplan::python {
namespace {

// The planner with what it refers to, kept alive as long as it is.
struct PyBodyPlanner {
  std::shared_ptr<const RobotModel> robot;
  std::shared_ptr<const Staircase> stairs;
  std::shared_ptr<const PipelineResult> plan;
  std::unique_ptr<BodyPlanner> planner;
};

py::array_t<double> Knots(const std::vector<BodyState>& knots) {
  py::array_t<double> out({static_cast<py::ssize_t>(knots.size()), py::ssize_t{8}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < knots.size(); ++k) {
    const BodyState& s = knots[k];
    const double row[] = {s.t, s.x, s.y, s.z, s.pitch, s.yaw, s.com_shift, s.com_shift_y};
    for (int j = 0; j < 8; ++j) a(static_cast<py::ssize_t>(k), j) = row[j];
  }
  return out;
}

void BindState(py::module_& m) {
  py::class_<BodyState>(m, "BodyState", "The body at one instant: t, x, y, z, pitch, yaw, com_shift, com_shift_y (SI).")
      .def(py::init([](double t, double x, double y, double z, double pitch, double yaw, double com_shift,
                       double com_shift_y) { return BodyState{t, x, y, z, pitch, yaw, com_shift, com_shift_y}; }),
           py::arg("t") = 0.0, py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("z") = 0.0, py::arg("pitch") = 0.0,
           py::arg("yaw") = 0.0, py::arg("com_shift") = 0.0, py::arg("com_shift_y") = 0.0)
      .def_readwrite("t", &BodyState::t)
      .def_readwrite("x", &BodyState::x)
      .def_readwrite("y", &BodyState::y)
      .def_readwrite("z", &BodyState::z)
      .def_readwrite("pitch", &BodyState::pitch)
      .def_readwrite("yaw", &BodyState::yaw)
      .def_readwrite("com_shift", &BodyState::com_shift)
      .def_readwrite("com_shift_y", &BodyState::com_shift_y)
      .def("__repr__", [](const BodyState& s) {
        return "BodyState(t=" + std::to_string(s.t) + ", x=" + std::to_string(s.x) + ", z=" + std::to_string(s.z) +
               ", pitch=" + std::to_string(s.pitch) + ")";
      });
  py::enum_<BodyPlanStatus>(m, "BodyPlanStatus")
      .value("OK", BodyPlanStatus::kOk)
      .value("STALE", BodyPlanStatus::kStale)
      .value("INFEASIBLE", BodyPlanStatus::kInfeasible);
  py::class_<LegTarget>(m, "LegTarget", "One leg now: stance, foot_W, target_W, t_liftoff, t_touchdown.")
      .def_readonly("stance", &LegTarget::stance)
      .def_readonly("foot_W", &LegTarget::foot_W)
      .def_readonly("target_W", &LegTarget::target_W)
      .def_readonly("t_liftoff", &LegTarget::t_liftoff)
      .def_readonly("t_touchdown", &LegTarget::t_touchdown);
  py::class_<BodyPlannerOutput>(m, "BodyPlannerOutput",
                                "What update() returns: the planner's own output, overwritten by the next update().")
      .def_readonly("status", &BodyPlannerOutput::status)
      .def_property_readonly("solve_status", [](const BodyPlannerOutput& o) { return std::string(optim::ToString(o.solve_status)); })
      .def_property_readonly("knots", [](const BodyPlannerOutput& o) { return Knots(o.knots); },
                             "(knots, 8) array: t, x, y, z, pitch, yaw, com_shift, com_shift_y (a copy).")
      .def_property_readonly("reference", [](const BodyPlannerOutput& o) { return o.knots.front(); },
                             "The first knot: the body reference now.")
      .def_property_readonly("feet", [](const BodyPlannerOutput& o) {
        return std::vector<LegTarget>(o.feet.begin(), o.feet.end());
      }, "The four legs' targets, LF, RF, LH, RH.")
      .def_readonly("conflicts", &BodyPlannerOutput::conflicts)
      .def_readonly("next_violation", &BodyPlannerOutput::next_violation)
      .def_readonly("iterations", &BodyPlannerOutput::iterations)
      .def_readonly("solves", &BodyPlannerOutput::solves)
      .def_property_readonly("total_us", [](const BodyPlannerOutput& o) { return o.timings.total_us; },
                             "The C++ Update's own time [us].");
}

}  // namespace

void BindBody(py::module_& m) {
  BindState(m);
  py::class_<PyBodyPlanner>(m, "BodyPlanner", R"(The receding-horizon body QP for a control loop.

BodyPlanner(plan, horizon=20): over a Plan's footsteps, stairs, robot and map (plan.map), with
the support, leg and clearance rows `plan` plans with.
Each cycle: out = planner.update(state, now); track out.reference and out.feet. update() does
not allocate after the first call and releases no GIL (with the leg rows it takes 0.3-5 ms of CPU
on the built-in robot's climb: bench/body_planner_bench).)")
      .def(py::init([](const PlanResult& p, int horizon) {
        if (p.result->plan.status != PlanStatus::kOk) {
          throw std::invalid_argument("plan: status is infeasible (" + p.result->plan.status_reason + ")");
        }
        BodyPlannerSettings settings = PipelineOptions{}.body_qp;
        settings.knots = horizon;
        PyBodyPlanner out{p.robot, p.stairs, p.result, nullptr};
        py::gil_scoped_release release;
        out.planner = std::make_unique<BodyPlanner>(*out.robot, *out.stairs, out.plan->map, out.plan->plan, settings);
        return out;
      }), py::arg("plan"), py::arg("horizon") = PipelineOptions{}.body_qp.knots)
      .def("update", [](PyBodyPlanner& p, const BodyState& state, double now, double height_offset,
                        double pitch_offset) -> const BodyPlannerOutput& {
        return p.planner->Update(state, BodyCommand{height_offset, pitch_offset}, now);
      }, py::arg("state"), py::arg("now"), py::arg("height_offset") = 0.0, py::arg("pitch_offset") = 0.0,
           py::return_value_policy::reference_internal,
           "One cycle at time `now` [s] from the measured state; ValueError for a non-finite state or time.")
      .def("start_state", [](const PyBodyPlanner& p) { return p.planner->StartState(); },
           "The neutral body over the initial feet at the desired hip height.")
      .def("interpolate", [](const PyBodyPlanner& p, double t) { return p.planner->Interpolate(t); }, py::arg("t"),
           "The body reference at time t from the latest plan.")
      .def("reset", [](PyBodyPlanner& p) { p.planner->Reset(); }, "Forgets the previous plan.")
      .def_property_readonly("end_time", [](const PyBodyPlanner& p) { return p.planner->schedule().end_time(); })
      .def_property_readonly("desired_hip_height", [](const PyBodyPlanner& p) { return p.planner->desired_hip_height(); });
}

}  // namespace stairplan::python
