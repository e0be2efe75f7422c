// The robot's collision shapes: grouped by leg and body, posed with the leg's frames.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>

#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "../kinematics/robot_files.h"

using stairplan::RobotCollisionModel;
using stairplan::RobotKinematics;
using stairplan::RobotModel;

TEST_CASE("stairbot: four shapes per leg, the foot sphere flagged, the body box", "[robot_collision_model]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  const RobotCollisionModel model(kinematics);
  REQUIRE(model.body_shapes().size() == 1);
  CHECK(model.body_shapes()[0].type == stairplan::ShapeType::kBox);
  for (int l = 0; l < 4; ++l) {
    const auto& shapes = model.leg_shapes(l);
    REQUIRE(shapes.size() == 4);
    int contacts = 0;
    for (const auto& s : shapes) contacts += s.foot_contact;
    CHECK(contacts == 1);
  }
  // The foot sphere sits on the foot link's origin.
  const auto& leg = kinematics.leg("LH");
  stairplan::LegWorkspace ws(leg);
  const Eigen::Vector3d q(0.2, 0.4, -1.0);
  const auto& frames = leg.LinkFrames(q, ws);
  for (const auto& s : model.leg_shapes(kinematics.LegIndex("LH"))) {
    if (!s.foot_contact) continue;
    CHECK(((frames[static_cast<std::size_t>(s.segment)] * s.local).translation() - leg.FootPosition(q, ws)).norm() < 1e-12);
  }
}

TEST_CASE("real robots: fixed sub-links ride with their leg, sensors with the body", "[robot_collision_model]") {
  const auto robots = stairplan::testing::TestRobots(false);
  if (robots.empty()) {
    WARN("shared robots skipped: ../shared not found");
    return;
  }
  for (const auto& file : robots) {
    INFO(file.label);
    const RobotKinematics kinematics(RobotModel::FromUrdfFile(file.path));
    const RobotCollisionModel model(kinematics);
    for (int l = 0; l < 4; ++l) {
      int contacts = 0;
      for (const auto& s : model.leg_shapes(l)) contacts += s.foot_contact;
      CHECK(contacts == 1);
    }
    CHECK_FALSE(model.body_shapes().empty());
    const auto links_of = [&](int l) {
      std::set<std::string> links;
      for (const auto& s : model.leg_shapes(l)) links.insert(s.link);
      return links;
    };
    if (file.label == "unitree_go1") {
      // Thigh and calf rotors are fixed to the hip and thigh links; the hip rotor to the trunk.
      CHECK(links_of(0).count("FL_thigh_rotor") == 1);
      CHECK(links_of(0).count("FL_calf_rotor") == 1);
      bool hip_rotor_on_body = false;
      for (const auto& s : model.body_shapes()) hip_rotor_on_body = hip_rotor_on_body || s.link == "FL_hip_rotor";
      CHECK(hip_rotor_on_body);
    }
    if (file.label == "anymal_c") {
      // The shank tube is a cylinder of the FOOT link, next to the contact sphere.
      int cylinders = 0;
      for (const auto& s : model.leg_shapes(0)) cylinders += (s.link == "LF_FOOT" && s.type == stairplan::ShapeType::kCylinder);
      CHECK(cylinders == 1);
    }
    if (file.label == "unitree_go2") CHECK(links_of(1).count("FR_calflower1") == 1);
  }
}

TEST_CASE("shapes fixed below the knee's link are the foot's parts, the foot sphere is named", "[robot_collision_model]") {
  const RobotKinematics stairbot(stairplan::BuiltinRobot());
  const RobotCollisionModel model(stairbot);
  for (int l = 0; l < 4; ++l) {
    const auto& shapes = model.leg_shapes(l);
    REQUIRE(model.foot_shape(l) >= 0);
    CHECK(shapes.at(static_cast<std::size_t>(model.foot_shape(l))).foot_contact);
    for (const auto& s : shapes) {
      // stairbot: only the foot link (fixed to the shank, the knee's link) is a foot part.
      INFO(s.link);
      CHECK(s.foot_part == (s.link.find("foot") != std::string::npos));
    }
  }
  const auto robots = stairplan::testing::TestRobots(false);
  const auto b = std::find_if(robots.begin(), robots.end(), [](const auto& r) { return r.label == "anymal_b"; });
  if (b == robots.end()) return;
  // ANYmal B: SHANK (the knee's link) -> ADAPTER -> FOOT by fixed joints; the last two are the foot.
  const RobotKinematics anymal(RobotModel::FromUrdfFile(b->path));
  const RobotCollisionModel anymal_model(anymal);
  std::set<std::string> foot, rest;
  for (const auto& s : anymal_model.leg_shapes(anymal.LegIndex("LH"))) (s.foot_part ? foot : rest).insert(s.link);
  CHECK(foot == std::set<std::string>{"LH_ADAPTER", "LH_FOOT"});
  CHECK(rest == std::set<std::string>{"LH_HIP", "LH_THIGH", "LH_SHANK"});
}
