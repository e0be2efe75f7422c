// Our MJCF writer against MuJoCo itself: every robot loads with the URDF's mass and joints, and
// the built-in robot stands on the landing under PD control with only its feet touching.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <set>

#include <mujoco/mujoco.h>
#include <unistd.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/simulation/mujoco_world.h"
#include "test_paths.h"

using namespace stairplan;

namespace {

int LegJointCount(const RobotModel& robot) {
  int n = 0;
  for (const LegModel& leg : robot.legs()) n += static_cast<int>(leg.joint_names.size());
  return n;
}

}  // namespace

TEST_CASE("the built-in robot's MJCF loads with its URDF mass, joints and motors", "[mujoco]") {
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs(StairSpec{});
  MujocoWorld world(robot, stairs);
  CHECK(world.model()->nu == 12);
  CHECK(world.model()->njnt == 13);  // 12 leg joints and the free base
  CHECK(world.RobotMass() == Approx(robot.total_mass()).epsilon(1e-9));
  int stair_geoms = 0;
  for (int g = 0; g < world.model()->ngeom; ++g) {
    const char* name = mj_id2name(world.model(), mjOBJ_GEOM, g);
    stair_geoms += (name != nullptr && std::string(name).rfind("stair_", 0) == 0) ? 1 : 0;
  }
  CHECK(stair_geoms == static_cast<int>(stairs.Solids().size()));
  // Joint limits carried over from the URDF.
  const int knee = mj_name2id(world.model(), mjOBJ_JOINT, "LF_KFE");
  REQUIRE(knee >= 0);
  CHECK(world.model()->jnt_range[2 * knee] == Approx(-2.6));
  CHECK(world.model()->jnt_range[2 * knee + 1] == Approx(-0.35));
}

TEST_CASE("the shared robots load in MuJoCo through our writer", "[mujoco]") {
  if (testing::SharedDir().empty()) {
    WARN("skipped: ../shared not found");
    return;
  }
  for (const char* file : {"unitree_a1.urdf", "unitree_go1.urdf", "unitree_go2.urdf", "anymal_b.urdf", "anymal_c.urdf"}) {
    INFO(file);
    const RobotModel robot = RobotModel::FromUrdfFile(testing::SharedPath(std::string("data/robots/") + file));
    MujocoWorld world(robot, Staircase(StairSpec{}));
    CHECK(world.model()->nu == LegJointCount(robot));
    CHECK(world.RobotMass() == Approx(robot.total_mass()).epsilon(0.02));
  }
}

TEST_CASE("no two links of a robot touch in MuJoCo while it hangs in the air", "[mujoco]") {
  // ANYmal B's base boxes reach 2.5 mm into its thighs at every pose: MuJoCo held four contacts
  // between them, pushing base and thighs apart with forces the robot never feels, and its
  // descent on the default path fell by roll at t = 5.8 s (it succeeds without them).
  std::vector<std::pair<std::string, RobotModel>> robots;
  robots.emplace_back("stairbot", BuiltinRobot());
  if (testing::SharedDir().empty()) {
    WARN("shared robots skipped: ../shared not found");
  } else {
    for (const char* file : {"unitree_a1.urdf", "unitree_go1.urdf", "unitree_go2.urdf", "anymal_b.urdf", "anymal_c.urdf"}) {
      robots.emplace_back(file, RobotModel::FromUrdfFile(testing::SharedPath(std::string("data/robots/") + file)));
    }
  }
  for (const auto& [name, robot] : robots) {
    MujocoWorld world(robot, Staircase(StairSpec{}));
    world.SetBasePose({0.0, 0.0, 5.0}, 0.0, 0.0);  // far above the stairs, joints at zero
    mj_forward(world.model(), world.data());
    INFO(name << ": " << world.data()->ncon << " contacts, the first between "
              << (world.data()->ncon > 0 ? mj_id2name(world.model(), mjOBJ_GEOM, world.data()->contact[0].geom1) : "-")
              << " and " << (world.data()->ncon > 0 ? mj_id2name(world.model(), mjOBJ_GEOM, world.data()->contact[0].geom2) : "-"));
    CHECK(world.data()->ncon == 0);
  }
}

TEST_CASE("MuJoCo's warnings go to stderr, not into stdout where simulate --json writes", "[mujoco]") {
  // Made with its base 1 m up, Go1's world at the top of a descent sinks its legs into the
  // landing's blocks: MuJoCo warns that its contact buffer is full. On stdout that line made the
  // JSON of `simulate --json` unreadable (ANYmal B's descent).
  if (testing::SharedDir().empty()) {
    WARN("skipped: ../shared not found");
    return;
  }
  const RobotModel robot = RobotModel::FromUrdfFile(testing::SharedPath("data/robots/unitree_go1.urdf"));
  std::fflush(stdout);
  std::FILE* captured = std::tmpfile();
  REQUIRE(captured != nullptr);
  const int saved = dup(fileno(stdout));
  dup2(fileno(captured), fileno(stdout));
  {
    StairSpec spec;
    spec.direction = TravelDirection::kDown;
    MujocoWorld world(robot, Staircase(spec));
    for (int step = 0; step < 5; ++step) world.Step();
  }
  std::fflush(stdout);
  dup2(saved, fileno(stdout));
  close(saved);
  std::fseek(captured, 0, SEEK_END);
  CHECK(std::ftell(captured) == 0);
  std::fclose(captured);
}

TEST_CASE("names holding XML's special characters reach MuJoCo unchanged", "[mujoco]") {
  // Legal URDF names may hold quotes, '&' and '<' (written as references in the file); copied
  // into the MJCF as they were, an apostrophe broke its XML and `simulate` exited 1 (issue #28).
  std::string urdf = BuiltinRobotUrdf();
  const auto replace_all = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = 0; (at = urdf.find(from, at)) != std::string::npos; at += to.size()) urdf.replace(at, from.size(), to);
  };
  replace_all("\"LF_foot\"", "\"LF&apos;foot &amp; &lt;1&gt;\"");
  replace_all("\"LF_KFE\"", "\"LF&quot;KFE\"");
  replace_all("<robot name=\"stairbot\">", "<robot name=\"stair'bot\">");
  const RobotModel robot = RobotModel::FromUrdfString(urdf, "quotes.urdf");
  REQUIRE(robot.name() == "stair'bot");
  MujocoWorld world(robot, Staircase(StairSpec{}));
  CHECK(mj_name2id(world.model(), mjOBJ_BODY, "LF'foot & <1>") >= 0);
  CHECK(mj_name2id(world.model(), mjOBJ_JOINT, "LF\"KFE") >= 0);
  CHECK(mj_name2id(world.model(), mjOBJ_ACTUATOR, "LF\"KFE_motor") >= 0);
  CHECK(world.model()->nu == 12);
}

TEST_CASE("the built-in robot stands on the landing under PD control", "[mujoco]") {
  const RobotModel& robot = BuiltinRobot();
  MujocoWorld world(robot, Staircase(StairSpec{}));
  // Thigh 0.7 rad back, knee -1.4 rad: each foot straight below its hip, 0.459 m down.
  std::vector<std::pair<int, int>> joints;  // (qpos, motor) per joint
  std::vector<double> target;
  for (const LegModel& leg : robot.legs()) {
    for (std::size_t i = 0; i < leg.joint_names.size(); ++i) {
      joints.emplace_back(world.QposIndex(leg.joint_names[i]), world.MotorIndex(leg.joint_names[i]));
      target.push_back(i == 0 ? 0.0 : (i == 1 ? 0.7 : -1.4));
    }
  }
  for (std::size_t j = 0; j < joints.size(); ++j) world.data()->qpos[joints[j].first] = target[j];
  world.SetBasePose({-0.6, 0.0, 0.49}, 0.0, 0.0);
  for (int step = 0; step < 1500; ++step) {
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const int dof = world.model()->jnt_dofadr[world.model()->actuator_trnid[2 * joints[j].second]];
      const double q = world.data()->qpos[joints[j].first], qd = world.data()->qvel[dof];
      world.data()->ctrl[joints[j].second] = 200.0 * (target[j] - q) - 5.0 * qd + world.data()->qfrc_bias[dof];
    }
    world.Step();
  }
  const Eigen::Vector3d base = world.BasePosition();
  const Eigen::Vector3d rpy = world.BaseRollPitchYaw();
  CHECK(base.z() > 0.40);
  CHECK(base.z() < 0.50);
  CHECK(std::abs(rpy.x()) < 0.05);
  CHECK(std::abs(rpy.y()) < 0.05);
  std::set<std::string> touching;
  for (const StairContact& c : world.StairContacts()) touching.insert(c.body);
  CHECK(touching == std::set<std::string>{"LF_foot", "RF_foot", "LH_foot", "RH_foot"});
}
