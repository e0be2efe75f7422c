// `stairplan robot [URDF]`: the robot summary: legs and their names, hips, joint limits, where each
// foot touches the ground (a sphere's bottom, or a mesh foot's lowest point along the leg in the
// nominal stance), the collision meshes and what loading them cost.
#include <chrono>
#include <iostream>

#include <nlohmann/json.hpp>

#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "cli/cli_common.h"

namespace stairplan::cli {
namespace {

nlohmann::json RobotXyz(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json LegJson(const LegKinematics& leg) {
  const LegModel& m = leg.model();
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t j = 0; j < m.joint_names.size(); ++j) {
    joints.push_back({{"name", m.joint_names[j]}, {"lower", m.limits[j].lower}, {"upper", m.limits[j].upper},
                      {"effort", m.limits[j].effort}});
  }
  return {{"name", m.name}, {"foot_link", m.foot_link}, {"hip_B", RobotXyz(m.hip_B)}, {"joints", joints},
          {"max_reach_m", m.max_reach}, {"nominal_q", RobotXyz(leg.nominal())},
          {"foot_contact", ToString(m.foot_contact)},
          {"foot_contact_point_in_foot_link",
           RobotXyz(m.foot_contact == FootContact::kMeshLowestPoint ? m.foot_contact_point : m.foot_sphere_center)},
          {"foot_sphere_center_in_foot_link", RobotXyz(m.foot_sphere_center)}, {"foot_radius_m", m.foot_radius}};
}

// Mesh shapes of the collision model: how many, and their hulls' sizes.
nlohmann::json MeshJson(const RobotCollisionModel& collision) {
  int shapes = 0, hull_vertices = 0;
  const auto count = [&](const std::vector<CollisionShape>& list) {
    for (const CollisionShape& s : list) {
      if (s.type != ShapeType::kMesh) continue;
      ++shapes;
      hull_vertices += static_cast<int>(s.mesh->hull_vertices.size());
    }
  };
  count(collision.body_shapes());
  for (int l = 0; l < collision.leg_count(); ++l) count(collision.leg_shapes(l));
  return {{"mesh_shapes", shapes}, {"hull_vertices", hull_vertices}};
}

void PrintSummary(const nlohmann::json& j) {
  std::cout << "stairplan robot: " << j["name"].get<std::string>() << " (" << j["source"].get<std::string>() << "), base "
            << j["base_link"].get<std::string>() << ", " << j["mass_kg"].get<double>() << " kg\n";
  for (const auto& leg : j["legs"]) {
    const auto& c = leg["foot_contact_point_in_foot_link"];
    std::cout << "  " << leg["name"].get<std::string>() << ": foot " << leg["foot_link"].get<std::string>()
              << ", hip at (" << leg["hip_B"][0] << ", " << leg["hip_B"][1] << ", " << leg["hip_B"][2]
              << ") m, contact " << leg["foot_contact"].get<std::string>() << " at (" << c[0] << ", " << c[1] << ", "
              << c[2] << ") m in the foot link";
    if (leg["foot_contact"] == "mesh_lowest_point" && leg["foot_radius_m"].get<double>() > 0.0) {
      std::cout << ", rolling as a sphere of radius " << leg["foot_radius_m"].get<double>() << " m";
    }
    std::cout << "\n";
  }
  const auto& m = j["meshes"];
  std::cout << "  meshes: " << m["collision_meshes"] << " collision meshes as " << m["collision"].get<std::string>()
            << " (" << m["mesh_shapes"] << " on legs and body, " << m["hull_vertices"] << " hull vertices); "
            << m["files_read"] << " files read; load " << j["load_ms"] << " ms, collision model "
            << j["collision_model_ms"] << " ms\n";
}

int RunRobot(const std::vector<std::string>& args) {
  CLI::App app("Summarise a robot: legs, hips, limits, foot contacts, collision meshes, loading cost", "robot");
  std::string path;
  RobotFlags flags;
  bool json = false;
  app.add_option("urdf", path, "Robot URDF file (default: the built-in stairbot)");
  AddRobotFlags(app, flags);
  app.add_flag("--json", json, "Print JSON instead of the summary");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("robot", [&] {
    const auto t_load = std::chrono::steady_clock::now();
    const RobotModel robot = LoadRobot(path, flags);
    const double load_ms = MillisecondsSince(t_load);
    const auto t_collision = std::chrono::steady_clock::now();
    const RobotKinematics kinematics(robot);
    const RobotCollisionModel collision(kinematics);
    const double collision_ms = MillisecondsSince(t_collision);
    nlohmann::json j = {{"name", robot.name()}, {"source", robot.source()}, {"base_link", robot.base_link()},
                        {"mass_kg", robot.total_mass()}, {"hip_length_m", robot.hip_length()},
                        {"hip_width_m", robot.hip_width()}, {"load_ms", load_ms}, {"collision_model_ms", collision_ms}};
    j["legs"] = nlohmann::json::array();
    for (const LegKinematics& leg : kinematics.legs()) j["legs"].push_back(LegJson(leg));
    j["meshes"] = MeshJson(collision);
    j["meshes"]["collision_meshes"] = robot.meshes().size();
    j["meshes"]["collision"] = ToString(robot.meshes().collision());
    j["meshes"]["files_read"] = MeshFilesRead();
    if (json) {
      std::cout << j.dump(2) << "\n";
    } else {
      PrintSummary(j);
    }
    return kExitOk;
  });
}

const CommandRegistrar kRobotRegistrar({"robot", "summarise a robot: legs, foot contacts, meshes, loading cost", RunRobot});

}  // namespace
}  // namespace stairplan::cli
