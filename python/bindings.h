// What the binding translation units of the Python module share: one Bind* function per area
// and the conversions between Python objects and the library's JSON and arrays.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

/// The Python module's C++ side (stairplan/planning/python): bindings and conversions.
namespace stairplan::python {

namespace py = pybind11;

/// A file named by the caller is missing: Python's FileNotFoundError with `filename` set.
class FileNotFound : public std::runtime_error {
 public:
  /// `path`: the missing file.
  explicit FileNotFound(const std::string& path)
      : std::runtime_error("no such file: '" + path + "'"), path_(path) {}
  /// The missing file.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

///@{
/// Adds one area's classes and functions to the module `m`.
void BindGeometry(py::module_& m);
void BindPlan(py::module_& m);
void BindSweep(py::module_& m);
void BindOptim(py::module_& m);
void BindBody(py::module_& m);
///@}

/// JSON as Python objects (dict, list, str, float, int, bool, None). Non-finite numbers become
/// None, as nlohmann's dump() writes them, so to_dict() equals the parsed file.
py::object ToPython(const nlohmann::json& json);
/// Python objects (dict, list, tuple, str, os.PathLike, numbers, numpy scalars and arrays, None)
/// as JSON; TypeError naming `where` for anything else.
nlohmann::json FromPython(const py::handle& object, const std::string& where);
/// A str or os.PathLike as a path; TypeError naming `what` otherwise.
std::string PathArg(const py::handle& object, const std::string& what);
/// Throws FileNotFound unless `path` is a regular file.
void RequireFile(const std::string& path);
/// A numpy structured array from equally long columns (name, numpy array or list).
py::object StructuredArray(const std::vector<std::pair<std::string, py::object>>& columns);

}  // namespace stairplan::python

// The shared argument conversions (bind_geometry.cc) and the perceived stairs a plan may run on.
#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/stair_frame.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"

namespace stairplan::python {

/// Stairs found in a point cloud: the staircase and the constrained map in its own frame, and the
/// fit (a dict).
struct Perceived {
  bool found = false;  ///< stairs were found
  std::string reason;  ///< why not, when not found
  std::shared_ptr<Staircase> stairs;  ///< the fitted staircase, when found
  std::shared_ptr<ConstrainedMap> map;  ///< its constrained map, when found
  std::shared_ptr<StairFrame> frame;  ///< the stairs' frame in the cloud's world, when found
  py::dict fit;  ///< the tracker's fit
};

/// None (the CLI's default stairs), a Stairs, a dict of stairs YAML keys or a YAML file, with the
/// stair fields of `overrides` on top.
Staircase StairsArg(const py::handle& stairs, const nlohmann::json& overrides);
/// None (the built-in stairbot), a Robot, or a URDF path.
RobotModel RobotArg(const py::handle& robot);

}  // namespace stairplan::python

#include "stairplan/pipeline/plan_pipeline.h"

namespace stairplan::python {

/// A plan with what it was planned for: the robot, the stairs, the map, the validation and the
/// plan.json object (what `stairplan plan` writes, without its "load" timing).
struct PlanResult {
  std::shared_ptr<const RobotModel> robot;  ///< the robot planned for
  std::shared_ptr<const Staircase> stairs;  ///< the stairs planned on
  std::shared_ptr<const PipelineResult> result;  ///< the map, plan and validation
  nlohmann::json json;  ///< the plan.json object
};

}  // namespace stairplan::python
