// Shared pieces of the `stairplan` sub-commands: registration, exit codes, error handling, and
// writing output files so that nothing half-written is ever left behind.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan_json_reader.h"

namespace stairplan::cli {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitInfeasible = 3;

/// Bad input whose message already names the flag, file or field.
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input is well formed but has no solution (e.g. a cloud with no stairs): exit 3.
class NoSolution : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One sub-command: `stairplan <name> ...`. `run` gets the arguments after the name.
struct Command {
  std::string name;
  std::string summary;
  std::function<int(const std::vector<std::string>& args)> run;
};

/// All registered sub-commands, sorted by name.
std::vector<Command>& Commands();

/// Registers a command at static-initialisation time (one per *_command.cc).
struct CommandRegistrar {
  explicit CommandRegistrar(Command command);
};

/// Parses `args` with `app`; returns -1 to go on, or the exit code (0 after --help, 2 on errors).
int Parse(CLI::App& app, const std::vector<std::string>& args);

/// Runs `body`, turning bad-input exceptions into a message on stderr and exit code 2 (NoSolution: 3).
int Guarded(const std::string& command, const std::function<int()>& body);

/// Writes `contents` to `path` through a temporary file and a rename; throws BadInput on failure.
void WriteFileAtomically(const std::string& path, const std::string& contents);

/// How every command that takes a robot finds and models its collision meshes.
struct RobotFlags {
  std::string package_path;            ///< --package-path DIR[:DIR...], before ROS_PACKAGE_PATH
  std::string mesh_collision = "hull";  ///< --mesh-collision hull|exact
};
/// Adds --package-path and --mesh-collision to `app`.
void AddRobotFlags(CLI::App& app, RobotFlags& flags);

/// The robot named by --robot: the built-in stairbot when `path` is empty; BadInput when missing.
RobotModel LoadRobot(const std::string& path, const RobotFlags& flags = {});

/// The robot a plan.json names (a URDF path or the built-in robot), unless --robot overrides it.
RobotModel LoadPlanRobot(const PlanFile& file, const std::string& override_path, const RobotFlags& flags = {});

/// Creates `dir` (and parents) or throws BadInput naming the flag.
void MakeOutputDir(const std::string& dir, const std::string& flag);

}  // namespace stairplan::cli
