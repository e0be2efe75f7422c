#include "cli/cli_common.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "stairplan/geometry/field_error.h"
#include "stairplan/kinematics/builtin_robot.h"

namespace stairplan::cli {

std::vector<Command>& Commands() {
  static std::vector<Command> commands;
  return commands;
}

CommandRegistrar::CommandRegistrar(Command command) {
  auto& commands = Commands();
  commands.push_back(std::move(command));
  std::sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) { return a.name < b.name; });
}

int Parse(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 consumes from the back
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    std::cerr << "stairplan " << app.get_name() << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  return -1;
}

int Guarded(const std::string& command, const std::function<int()>& body) {
  try {
    return body();
  } catch (const NoSolution& e) {
    std::cerr << "stairplan " << command << ": " << e.what() << "\n";
    return kExitInfeasible;
  } catch (const BadInput& e) {
    std::cerr << "stairplan " << command << ": " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "stairplan " << command << ": " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "stairplan " << command << ": error: " << e.what() << "\n";
    return 1;
  }
  return kExitBadInput;
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw BadInput(path + ": cannot open for writing");
    out << contents;
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      throw BadInput(path + ": write failed");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw BadInput(path + ": cannot rename the temporary file into place");
  }
}

void AddRobotFlags(CLI::App& app, RobotFlags& flags) {
  app.add_option("--package-path", flags.package_path,
                 "Folders searched for the robot's package:// mesh URIs, DIR[:DIR...] (then ROS_PACKAGE_PATH)");
  app.add_option("--mesh-collision", flags.mesh_collision,
                 "Collision meshes as their convex hulls (hull, default) or as the exact triangles (exact)");
}

RobotModel LoadRobot(const std::string& path, const RobotFlags& flags) {
  MeshSettings meshes;
  try {
    meshes.collision = ParseMeshCollision(flags.mesh_collision);
  } catch (const std::invalid_argument&) {
    throw BadInput("--mesh-collision: must be 'hull' or 'exact' (got '" + flags.mesh_collision + "')");
  }
  meshes.package_path = PackagePath::FromString(flags.package_path);
  if (path.empty()) return BuiltinRobot();
  if (!std::filesystem::is_regular_file(path)) throw BadInput("--robot: no such file '" + path + "'");
  return RobotModel::FromUrdfFile(path, {}, meshes);
}

RobotModel LoadPlanRobot(const PlanFile& file, const std::string& override_path, const RobotFlags& flags) {
  if (!override_path.empty()) return LoadRobot(override_path, flags);
  const std::string& source = file.plan.robot_source;
  if (source.empty() || source.rfind("builtin:", 0) == 0) return LoadRobot("", flags);
  return LoadRobot(source, flags);
}

void MakeOutputDir(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw BadInput(flag + ": cannot create directory '" + dir + "'" + (ec ? ": " + ec.message() : ""));
  }
}

}  // namespace stairplan::cli
