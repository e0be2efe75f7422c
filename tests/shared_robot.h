// A robot of ../shared/data/robots by its file name (the URDFs without meshes), for tests that
// plan or measure with it.
#pragma once

#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include "stairplan/kinematics/robot_model.h"
#include "test_paths.h"

namespace stairplan::testing {

/// data/robots/NAME.urdf of ../shared; none, with a warning, where ../shared is absent.
inline std::optional<RobotModel> SharedRobot(const std::string& name) {
  const std::string path = SharedPath("data/robots/" + name + ".urdf");
  if (path.empty()) {
    WARN("shared robots skipped: ../shared not found");
    return std::nullopt;
  }
  return RobotModel::FromUrdfFile(path);
}

}  // namespace stairplan::testing
