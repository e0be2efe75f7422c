// Stairs, robots and perception: Staircase, RobotModel, point clouds to stairs and a constrained
// map, footfalls to staircases.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/perception/point_cloud.h"
#include "stairplan/perception/stair_perception.h"
#include "stairplan/geometry/stair_spec_yaml.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "pipeline_adapter.h"
#include "stairplan/planning/plan_json.h"

namespace stairplan::python {
namespace {

nlohmann::json Overrides(const py::kwargs& fields) { return FromPython(fields, ""); }

py::array_t<double> Rows3(const std::vector<Eigen::Vector3d>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int j = 0; j < 3; ++j) a(static_cast<py::ssize_t>(i), j) = points[i][j];
  }
  return out;
}

PointCloud CloudArg(const py::handle& cloud) {
  if (py::isinstance<py::str>(cloud) || py::hasattr(cloud, "__fspath__")) {
    const std::string path = PathArg(cloud, "cloud");
    RequireFile(path);
    return ReadPointCloud(path);
  }
  const auto points = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(cloud);
  if (!points || points.ndim() != 2 || points.shape(1) != 3) {
    throw FieldError("cloud", "must be a path or an (N, 3) array of points");
  }
  PointCloud out;
  auto a = points.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    const Eigen::Vector3d p(a(i, 0), a(i, 1), a(i, 2));
    if (!p.allFinite()) throw FieldError("cloud[" + std::to_string(i) + "]", "must be finite");
    out.points.push_back(p);
  }
  return out;
}

std::vector<Footfall> FootfallsArg(const py::handle& footfalls) {
  if (py::isinstance<py::str>(footfalls) || py::hasattr(footfalls, "__fspath__")) {
    const std::string path = PathArg(footfalls, "footfalls");
    RequireFile(path);
    return ReadFootfallCsv(path);
  }
  std::vector<Footfall> out;
  int i = 0;
  for (const auto& row : footfalls) {  // (t, leg, x, y, z): tuples, lists or structured-array rows
    const std::string where = "footfalls[" + std::to_string(i++) + "]";
    if (py::len(row) != 5) throw FieldError(where, "must be (t, leg, x, y, z)");
    Footfall f;
    f.t = py::float_(row[py::int_(0)]);
    f.leg = py::str(row[py::int_(1)]);
    f.position = {py::float_(row[py::int_(2)]), py::float_(row[py::int_(3)]), py::float_(row[py::int_(4)])};
    out.push_back(f);
  }
  return out;
}

py::dict FootfallStairsDict(const FootfallStaircase& s) {
  py::dict d;
  d["steps"] = s.model.steps;
  d["rise"] = s.model.rise;
  d["run"] = s.model.run;
  d["width"] = s.model.width;
  d["yaw_rad"] = s.model.yaw();
  d["traversal"] = ToString(s.traversal);
  d["center"] = py::make_tuple(s.model.center.x(), s.model.center.y());
  d["tread_heights"] = s.tread_heights;
  d["cluster_sizes"] = s.cluster_sizes;
  d["t_begin"] = s.t_begin;
  d["t_end"] = s.t_end;
  d["footfalls"] = s.footfalls;
  return d;
}

Perceived Perceive(const py::handle& cloud, const std::string& direction, const std::string& facing) {
  StairPerceptionSettings settings;
  settings.regions.travel = ParseDirection(direction, "direction");
  if (facing != "forward" && facing != "backward") {
    throw FieldError("facing", "must be 'forward' or 'backward' (got '" + facing + "')");
  }
  settings.regions.facing = facing == "forward" ? Facing::kForward : Facing::kBackward;
  const PointCloud points = CloudArg(cloud);
  StairPerception seen;
  {
    py::gil_scoped_release release;
    seen = PerceiveStairs(points, settings);
  }
  Perceived out;
  out.found = seen.stairs.has_value();
  out.reason = seen.fit.reason;
  const StairModel& m = seen.fit.model;
  out.fit["steps"] = m.steps;
  out.fit["rise"] = m.rise;
  out.fit["run"] = m.run;
  out.fit["width"] = m.width;
  out.fit["yaw_rad"] = m.yaw();
  out.fit["level_rms_m"] = seen.fit.level_rms;
  out.fit["edge_rms_m"] = seen.fit.edge_rms;
  out.fit["point_rms_m"] = seen.fit.point_rms;
  if (seen.stairs) {
    const Eigen::Vector3d origin = m.StairToWorld(Eigen::Vector3d::Zero(), settings.regions.travel);
    out.fit["plan_frame_origin_W"] = py::make_tuple(origin.x(), origin.y(), origin.z());
    out.fit["plan_frame_yaw_rad"] = m.TravelYaw(settings.regions.travel);
    out.stairs = std::make_shared<Staircase>(seen.stairs->stairs);
    out.map = std::make_shared<ConstrainedMap>(seen.stairs->map);
    out.frame = std::make_shared<StairFrame>(StairFrame{m, settings.regions.travel, settings.regions.nosing});
  }
  return out;
}

py::list Regions(const ConstrainedMap& map) {
  py::list out;
  for (const StairRegions& s : map.stairs()) {
    py::dict d;
    d["index"] = s.index;
    d["z"] = s.z;
    std::vector<std::pair<double, double>> step, surface;
    for (const auto& p : s.step_region.vertices) step.emplace_back(p.x(), p.y());
    for (const auto& p : s.surface.vertices) surface.emplace_back(p.x(), p.y());
    d["surface"] = surface;
    d["step_region"] = step;
    py::list collisions;
    for (const CollisionRegion& c : s.collision_regions) {
      std::vector<std::pair<double, double>> polygon;
      for (const auto& p : c.polygon.vertices) polygon.emplace_back(p.x(), p.y());
      collisions.append(py::dict(py::arg("kind") = ToString(c.kind), py::arg("polygon") = polygon));
    }
    d["collision_regions"] = collisions;
    out.append(d);
  }
  return out;
}

void BindStairs(py::module_& m) {
  py::class_<Staircase, std::shared_ptr<Staircase>>(m, "Stairs", R"(A staircase: per-step rises and runs, nosing, width, landings, direction.

Stairs(spec=None, **fields): `spec` is None (the defaults: 7 steps, rise 0.17, run 0.27,
nosing 0.02, width 1.0, up), a dict or a YAML file of the stairs YAML keys (steps, rise, run,
nosing, width, landing_before, landing_after, nosing_thickness, rises, runs, direction, uncertainty); the
keyword fields override it. Raises ValueError (stairplan.FieldError) naming a bad field and
FileNotFoundError for a missing file.)")
      .def(py::init([](const py::object& spec, const py::kwargs& fields) { return StairsArg(spec, Overrides(fields)); }),
           py::arg("spec") = py::none())
      .def_property_readonly("steps", &Staircase::steps)
      .def_property_readonly("rise", [](const Staircase& s) { return s.spec().rise; })
      .def_property_readonly("run", [](const Staircase& s) { return s.spec().run; })
      .def_property_readonly("nosing", [](const Staircase& s) { return s.spec().nosing; })
      .def_property_readonly("width", [](const Staircase& s) { return s.spec().width; })
      .def_property_readonly("uncertainty", [](const Staircase& s) { return s.spec().uncertainty; },
                             "How far the true nosings may be from these [m]; the planners keep it as clearance.")
      .def_property_readonly("direction", [](const Staircase& s) { return std::string(ToString(s.direction())); })
      .def_property_readonly("total_rise", &Staircase::total_rise)
      .def_property_readonly("rises", [](const Staircase& s) {
        std::vector<double> r;
        for (int k = 0; k < s.steps(); ++k) r.push_back(s.rise(k));
        return r;
      })
      .def("height_at", &Staircase::HeightAt, py::arg("x"), py::arg("y"),
           "Height of the walkable surface at (x, y) [m]; nan outside the stairs.")
      .def("to_dict", [](const Staircase& s) { return ToPython(StairsToJson(s)); },
           "The resolved staircase as plan.json's `stairs` object.")
      .def("__repr__", [](const Staircase& s) {
        return "Stairs(steps=" + std::to_string(s.steps()) + ", rise=" + std::to_string(s.spec().rise) +
               ", run=" + std::to_string(s.spec().run) + ", direction='" + ToString(s.direction()) + "')";
      });
}

void BindRobot(py::module_& m) {
  py::class_<RobotModel, std::shared_ptr<RobotModel>>(m, "Robot", R"(A legged robot read from URDF, legs LF, RF, LH, RH.

Robot(urdf=None): None is the built-in stairbot; otherwise a URDF file path. Raises
FileNotFoundError for a missing file and ValueError naming the URDF element for a bad one.)")
      .def(py::init([](const py::object& urdf) { return RobotArg(urdf); }), py::arg("urdf") = py::none())
      .def_static("from_urdf_string", [](const std::string& xml, const std::string& source) {
        return RobotModel::FromUrdfString(xml, source);
      }, py::arg("xml"), py::arg("source") = "<string>", "A robot from URDF text; `source` names it in errors.")
      .def_property_readonly("name", &RobotModel::name)
      .def_property_readonly("source", &RobotModel::source)
      .def_property_readonly("base_link", &RobotModel::base_link)
      .def_property_readonly("total_mass", &RobotModel::total_mass)
      .def_property_readonly("hip_length", &RobotModel::hip_length)
      .def_property_readonly("hip_width", &RobotModel::hip_width)
      .def_property_readonly("legs", [](const RobotModel& r) {
        py::list out;
        for (const LegModel& leg : r.legs()) {
          py::dict d;
          d["name"] = leg.name;
          d["foot_link"] = leg.foot_link;
          d["joint_names"] = leg.joint_names;
          std::vector<std::pair<double, double>> limits;
          for (const JointLimits& l : leg.limits) limits.emplace_back(l.lower, l.upper);
          d["joint_limits"] = limits;
          d["hip_B"] = py::make_tuple(leg.hip_B.x(), leg.hip_B.y(), leg.hip_B.z());
          d["max_reach"] = leg.max_reach;
          d["mass"] = leg.mass;
          out.append(d);
        }
        return out;
      }, "One dict per leg: name, foot_link, joint_names, joint_limits [(lower, upper)], hip_B, max_reach, mass.")
      .def("__repr__", [](const RobotModel& r) { return "Robot('" + r.name() + "', source='" + r.source() + "')"; });
}

void BindPerception(py::module_& m) {
  py::class_<ConstrainedMap, std::shared_ptr<ConstrainedMap>>(m, "ConstrainedMap",
      "Per stair surface: the step region where a foot may land and the collision regions.")
      .def_property_readonly("regions", &Regions,
                             "One dict per surface: index, z, surface, step_region, collision_regions [{kind, polygon}].");
  py::class_<Perceived>(m, "Perception", "Stairs perceived in a point cloud (stairplan.perceive).")
      .def_readonly("found", &Perceived::found)
      .def_readonly("reason", &Perceived::reason, "Why no stairs were found; empty when found.")
      .def_readonly("stairs", &Perceived::stairs, "The fitted Stairs in their own frame, or None.")
      .def_readonly("map", &Perceived::map, "The constrained map from the data, or None.")
      .def_readonly("fit", &Perceived::fit, "The tracker's model and residuals, and the plan frame in the world.");
  m.def("read_point_cloud", [](const py::object& path) { return Rows3(CloudArg(path).points); }, py::arg("path"),
        "Reads a PLY or XYZ point cloud into an (N, 3) array [m].");
  m.def("perceive", &Perceive, py::arg("cloud"), py::arg("direction") = "up", py::arg("facing") = "forward",
        R"(Point cloud (a path or an (N, 3) array, world frame) -> height map -> fitted stairs -> constrained map.

Returns a Perception; plan(stairs=perception) plans on its map as `stairplan plan --cloud` does.)");
  m.def("stairs_from_footfalls", [](const py::object& footfalls) {
    const std::vector<Footfall> steps = FootfallsArg(footfalls);
    std::vector<FootfallStaircase> found;
    {
      py::gil_scoped_release release;
      found = StairsFromFootfalls(steps);
    }
    py::list out;
    for (const auto& s : found) out.append(FootfallStairsDict(s));
    return out;
  }, py::arg("footfalls"), R"(The staircases a robot walked, from its footfalls.

`footfalls`: a CSV path (t,leg,x,y,z) or rows (t, leg, x, y, z). Returns one dict per staircase:
steps, rise, run, width, yaw_rad, traversal, center, tread_heights, cluster_sizes, t_begin, t_end.)");
}

}  // namespace

Staircase StairsArg(const py::handle& stairs, const nlohmann::json& overrides) {
  if (stairs.is_none()) return StairsFrom(StairSpec{}, overrides, "stairs");
  if (py::isinstance<Staircase>(stairs)) return StairsFrom(stairs.cast<const Staircase&>().spec(), overrides, "stairs");
  if (py::isinstance<py::dict>(stairs)) {
    return StairsFrom(StairSpecFrom(FromPython(stairs, "stairs"), "stairs"), overrides, "stairs");
  }
  const std::string path = PathArg(stairs, "stairs");
  RequireFile(path);
  return StairsFrom(StairSpecFromYamlFile(path), overrides, path);
}

RobotModel RobotArg(const py::handle& robot) {
  if (robot.is_none()) return BuiltinRobot();
  if (py::isinstance<RobotModel>(robot)) return robot.cast<RobotModel>();
  const std::string path = PathArg(robot, "robot");
  RequireFile(path);
  return RobotModel::FromUrdfFile(path);
}

void BindGeometry(py::module_& m) {
  BindStairs(m);
  BindRobot(m);
  BindPerception(m);
}

}  // namespace stairplan::python
