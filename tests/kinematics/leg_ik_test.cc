// Position IK: round trips on every robot, statuses for unreachable targets, misuse.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <random>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "robot_files.h"

using stairplan::IkResult;
using stairplan::IkStatus;
using stairplan::LegKinematics;
using stairplan::LegWorkspace;
using stairplan::RobotKinematics;
using stairplan::RobotModel;

TEST_CASE("IK round trip from the nominal seed on 10,000 random configurations per robot", "[leg_ik]") {
  const auto robots = stairplan::testing::TestRobots();
  if (robots.size() == 1) WARN("shared robots skipped: ../shared not found");
  for (const auto& file : robots) {
    INFO(file.label);
    const RobotKinematics kinematics(file.path.empty() ? stairplan::BuiltinRobot() : RobotModel::FromUrdfFile(file.path));
    std::vector<LegWorkspace> workspaces;
    for (const LegKinematics& leg : kinematics.legs()) workspaces.emplace_back(leg);
    std::mt19937 rng(42);
    constexpr int kTrials = 10000;
    int solved = 0, round_trip_ok = 0;
    double seconds = 0.0, worst = 0.0;
    for (int trial = 0; trial < kTrials; ++trial) {
      const int l = trial % 4;
      const LegKinematics& leg = kinematics.leg(l);
      Eigen::Vector3d q;
      for (int j = 0; j < 3; ++j) q(j) = std::uniform_real_distribution<double>(leg.lower()(j), leg.upper()(j))(rng);
      const Eigen::Vector3d target = leg.FootPosition(q, workspaces[static_cast<std::size_t>(l)]);
      const auto start = std::chrono::steady_clock::now();
      const IkResult result = leg.SolveFootIk(target, workspaces[static_cast<std::size_t>(l)]);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      CHECK(leg.WithinLimits(result.q));
      const double error = (leg.FootPosition(result.q, workspaces[static_cast<std::size_t>(l)]) - target).norm();
      solved += result.ok();
      if (result.ok()) {
        worst = std::max(worst, error);
        round_trip_ok += error < 1e-6;
      }
    }
    std::printf("IK round trip %-12s success %.2f%%  mean %.2f us  worst error %.1e m\n", file.label.c_str(),
                100.0 * solved / kTrials, 1e6 * seconds / kTrials, worst);
    CHECK(round_trip_ok == solved);
    CHECK(solved >= 0.999 * kTrials);
  }
}

TEST_CASE("IK reports out of reach and joint limits, and keeps q within limits", "[leg_ik]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  const LegKinematics& leg = kinematics.leg("LF");
  LegWorkspace ws(leg);
  const IkResult far = leg.SolveFootIk(leg.hip_B() + Eigen::Vector3d(0.0, 0.0, -0.9), ws);
  CHECK(far.status == IkStatus::kOutOfReach);
  CHECK(far.error > 0.2);
  CHECK(leg.WithinLimits(far.q));
  // Farther than the links laid end to end: one descent and the answer (planners probe many).
  REQUIRE(0.9 > leg.model().max_reach);
  CHECK(far.iterations <= stairplan::IkSettings{}.max_iterations);
  // A nearly straight knee (KFE = -0.05) is beyond stairbot's KFE upper limit of -0.35, and no
  // other configuration reaches that far.
  const Eigen::Vector3d straight = leg.FootPosition(Eigen::Vector3d(0.0, 0.3, -0.05), ws);
  const IkResult limits = leg.SolveFootIk(straight, ws);
  CHECK(limits.status == IkStatus::kJointLimits);
  CHECK(leg.WithinLimits(limits.q));
  // Beyond the reach within the limits, so no restart is tried before the unlimited solve.
  CHECK(limits.iterations <= stairplan::IkSettings{}.max_iterations);
  CHECK(std::string(stairplan::ToString(limits.status)) == "joint_limits");
  const IkResult ok = leg.SolveFootIk(leg.FootPosition(Eigen::Vector3d(0.1, 0.6, -1.2), ws), ws);
  CHECK(ok.status == IkStatus::kSolved);
  CHECK(ok.error < 1e-9);
}

TEST_CASE("IK refuses NaN targets and bad settings", "[leg_ik]") {
  const RobotKinematics kinematics(stairplan::BuiltinRobot());
  const LegKinematics& leg = kinematics.leg("RH");
  LegWorkspace ws(leg);
  CHECK_THROWS_WITH(leg.SolveFootIk(Eigen::Vector3d(NAN, 0, 0), ws), Catch::Contains("foot_B"));
  stairplan::IkSettings settings;
  settings.tolerance = -1.0;
  CHECK_THROWS_WITH(settings.Validate(), Catch::Contains("tolerance"));
  CHECK_THROWS_WITH(leg.SolveFootIk(leg.hip_B(), ws, settings), Catch::Contains("IkSettings.tolerance"));
}
