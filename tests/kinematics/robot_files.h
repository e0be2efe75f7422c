// The robots every kinematics and collision test runs on: the five shared URDFs and stairbot.
#pragma once

#include <string>
#include <vector>

#include "test_paths.h"

namespace stairplan::testing {

struct RobotFile {
  std::string label;     ///< short name for messages
  std::string path;      ///< URDF file; empty for the built-in robot
  std::string foot_lf, foot_rf, foot_lh, foot_rh;  ///< expected foot links by leg name
};

/// The shared robots (empty when ../shared is absent) followed by the built-in stairbot.
inline std::vector<RobotFile> TestRobots(bool include_builtin = true) {
  std::vector<RobotFile> robots;
  if (!SharedDir().empty()) {
    for (const char* name : {"unitree_a1", "unitree_go1", "unitree_go2"}) {
      robots.push_back({name, SharedPath(std::string("data/robots/") + name + ".urdf"), "FL_foot", "FR_foot", "RL_foot", "RR_foot"});
    }
    for (const char* name : {"anymal_b", "anymal_c"}) {
      robots.push_back({name, SharedPath(std::string("data/robots/") + name + ".urdf"), "LF_FOOT", "RF_FOOT", "LH_FOOT", "RH_FOOT"});
    }
  }
  if (include_builtin) robots.push_back({"stairbot", "", "LF_foot", "RF_foot", "LH_foot", "RH_foot"});
  return robots;
}

}  // namespace stairplan::testing
