// stairplan.sweep(): plan and validate over a rise x run (x nosing x steps x direction) grid on
// threads, rows back as dicts or a numpy structured array, with a progress callback.
#include <mutex>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "stairplan/geometry/field_error.h"
#include "pipeline_adapter.h"

namespace stairplan::python {
namespace {

// A value V, a (lo, hi, count) triple or the CLI's "A:B:N".
SweepAxis AxisArg(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::str>(value)) return SweepAxis::Parse(value.cast<std::string>(), name);
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    const double v = value.cast<double>();
    return SweepAxis{v, v, 1};
  }
  const nlohmann::json t = FromPython(value, name);
  if (!t.is_array() || t.size() != 3 || !t[0].is_number() || !t[1].is_number() || !t[2].is_number_integer()) {
    throw FieldError(name, "must be a value, (lo, hi, count) or 'lo:hi:count'");
  }
  // The CLI's parser owns the axis rules (count >= 1, finite, lo <= hi).
  return SweepAxis::Parse(t[0].dump() + ":" + t[1].dump() + ":" + t[2].dump(), name);
}

py::list RowDicts(const std::vector<SweepRow>& rows) {
  py::list out;
  for (const SweepRow& r : rows) {
    py::dict d;
    d["index"] = r.point.index;
    d["direction"] = ToString(r.point.direction);
    d["steps"] = r.point.steps;
    d["nosing"] = r.point.nosing;
    d["rise"] = r.point.rise;
    d["run"] = r.point.run;
    d["status"] = r.status;
    d["reason"] = r.reason;
    d["cadence_s"] = r.cadence_s;
    d["footsteps"] = r.footsteps;
    d["gait"] = GaitName(r.gait);
    d["min_clearance_m"] = r.min_clearance_m;
    d["min_stability_margin_m"] = r.min_stability_margin_m;
    d["plan_us"] = r.plan_us;
    d["validate_us"] = r.validate_us;
    out.append(d);
  }
  return out;
}

py::object RowArray(const py::list& dicts) {
  const py::object numpy = py::module_::import("numpy");
  const std::pair<const char*, const char*> fields[] = {
      {"index", "i4"},   {"direction", "U4"}, {"steps", "i4"},     {"nosing", "f8"},
      {"rise", "f8"},    {"run", "f8"},       {"status", "U10"},   {"reason", "U"},
      {"cadence_s", "f8"}, {"footsteps", "i4"}, {"gait", "U16"}, {"min_clearance_m", "f8"}, {"min_stability_margin_m", "f8"},
      {"plan_us", "f8"}, {"validate_us", "f8"}};
  std::vector<std::pair<std::string, py::object>> columns;
  for (const auto& [name, dtype] : fields) {
    py::list values;
    for (const auto& d : dicts) values.append(d[name]);
    columns.emplace_back(name, numpy.attr("array")(values, py::arg("dtype") = dtype));
  }
  return StructuredArray(columns);
}

py::object Sweep(const py::object& robot_arg, const py::object& rise, const py::object& run, const py::object& nosing,
                 const py::object& steps, const py::object& directions, int threads, const py::object& progress,
                 bool as_array, const py::kwargs& kwargs) {
  SweepGrid grid;
  grid.rise = AxisArg(rise, "rise");
  grid.run = AxisArg(run, "run");
  grid.nosing = AxisArg(nosing, "nosing");
  grid.steps = AxisArg(steps, "steps");
  std::string direction_text;
  if (py::isinstance<py::str>(directions)) {
    direction_text = directions.cast<std::string>();
  } else {
    for (const auto& d : directions) direction_text += (direction_text.empty() ? "" : ",") + std::string(py::str(d));
  }
  grid.directions = ParseDirections(direction_text, "directions");
  if (threads < 1 || threads > 256) throw FieldError("threads", "must be from 1 to 256");
  const PipelineOptions options = PipelineOptionsFrom(FromPython(kwargs, ""));
  grid.facing = options.facing;
  const RobotModel robot = RobotArg(robot_arg);
  const std::vector<SweepPoint> points = EnumeratePoints(grid);

  // The callback runs on the worker threads (serialised by RunSweep): it takes the GIL, and its
  // first exception stops further calls and is raised once the sweep is done.
  std::exception_ptr callback_error;
  SweepProgress report;
  if (!progress.is_none()) {
    report = [&](int done, int total) {
      py::gil_scoped_acquire gil;
      if (callback_error) return;
      try {
        progress(done, total);
      } catch (py::error_already_set&) {
        callback_error = std::current_exception();
      }
    };
  }
  std::vector<SweepRow> rows;
  {
    py::gil_scoped_release release;
    rows = RunSweep(points, [&](const SweepPoint& p) { return EvaluateSweepPoint(p, robot, options); }, threads,
                    Shard{}, report);
  }
  if (callback_error) std::rethrow_exception(callback_error);
  const py::list dicts = RowDicts(rows);
  return as_array ? RowArray(dicts) : py::object(dicts);
}

}  // namespace

void BindSweep(py::module_& m) {
  m.def("sweep", &Sweep, py::arg("robot") = py::none(), py::arg("rise") = "0.10:0.25:20",
        py::arg("run") = "0.20:0.35:20", py::arg("nosing") = 0.02, py::arg("steps") = 7,
        py::arg("directions") = "up", py::arg("threads") = 1, py::arg("progress") = py::none(),
        py::arg("as_array") = false,
        R"(Plans and validates every point of a stair grid, as `stairplan sweep` (same defaults).

rise, run, nosing, steps: a value, (lo, hi, count) or 'lo:hi:count'; directions: 'up', 'down',
'up,down' or a list. options: plan()'s options (facing, planner, gait, body, ...). progress: called as
progress(done, total) after each point (from worker threads, holding the GIL). Returns one dict
per point in a fixed order (index, direction, steps, nosing, rise, run, status 'valid' |
'invalid' | 'infeasible' | 'bad_stairs', reason, cadence_s, footsteps, gait, min_clearance_m,
min_stability_margin_m, plan_us, validate_us), or with as_array=True a numpy structured array
with those fields. Releases the GIL.)");
}

}  // namespace stairplan::python
