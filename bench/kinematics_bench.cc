// Leg kinematics per call: foot FK, knee FK, all link frames, the foot Jacobian, and position IK
// from the nominal seed to random reachable targets. Robots: the built-in stairbot and, when
// ../shared is present, ANYmal C (rotated joint frames, 7 segments per chain) and Unitree A1.
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace {

using namespace stairplan;

const RobotKinematics& Robot(int index) {
  static const std::vector<RobotKinematics> robots = [] {
    std::vector<RobotKinematics> r;
    r.emplace_back(BuiltinRobot());
    for (const char* name : {"anymal_c", "unitree_a1"}) {
      const std::string path = std::string(STAIRPLAN_SHARED_DIR) + "/data/robots/" + name + ".urdf";
      if (std::filesystem::exists(path)) r.emplace_back(RobotModel::FromUrdfFile(path));
    }
    return r;
  }();
  return robots.at(static_cast<std::size_t>(index) % robots.size());
}

// Random configurations within the first leg's limits (fixed seed).
std::vector<Eigen::Vector3d> Configurations(const LegKinematics& leg, int count) {
  std::mt19937 rng(3);
  std::vector<Eigen::Vector3d> qs;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d q;
    for (int j = 0; j < 3; ++j) q(j) = std::uniform_real_distribution<double>(leg.lower()(j), leg.upper()(j))(rng);
    qs.push_back(q);
  }
  return qs;
}

template <typename F>
void RunOverConfigurations(benchmark::State& state, F&& call) {
  const RobotKinematics& robot = Robot(static_cast<int>(state.range(0)));
  const LegKinematics& leg = robot.leg(0);
  LegWorkspace ws(leg);
  const auto qs = Configurations(leg, 1024);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(call(leg, qs[i++ & 1023], ws));
  }
  state.SetLabel(robot.robot().name());
}

void BM_FootFk(benchmark::State& state) {
  RunOverConfigurations(state, [](const LegKinematics& leg, const Eigen::Vector3d& q, LegWorkspace& ws) {
    return leg.FootPosition(q, ws);
  });
}
void BM_KneeFk(benchmark::State& state) {
  RunOverConfigurations(state, [](const LegKinematics& leg, const Eigen::Vector3d& q, LegWorkspace& ws) {
    return leg.KneePosition(q, ws);
  });
}
void BM_LinkFrames(benchmark::State& state) {
  RunOverConfigurations(state, [](const LegKinematics& leg, const Eigen::Vector3d& q, LegWorkspace& ws) {
    return leg.LinkFrames(q, ws).back().translation();
  });
}
void BM_FootJacobian(benchmark::State& state) {
  RunOverConfigurations(state, [](const LegKinematics& leg, const Eigen::Vector3d& q, LegWorkspace& ws) {
    return leg.FootJacobian(q, ws);
  });
}

// IK from the nominal seed to the foot positions of random configurations within limits.
void BM_FootIk(benchmark::State& state) {
  const RobotKinematics& robot = Robot(static_cast<int>(state.range(0)));
  const LegKinematics& leg = robot.leg(0);
  LegWorkspace ws(leg);
  std::vector<Eigen::Vector3d> targets;
  for (const auto& q : Configurations(leg, 1024)) targets.push_back(leg.FootPosition(q, ws));
  std::size_t i = 0;
  int solved = 0, calls = 0;
  for (auto _ : state) {
    const IkResult r = leg.SolveFootIk(targets[i++ & 1023], ws);
    solved += r.ok();
    ++calls;
    benchmark::DoNotOptimize(r.q);
  }
  state.counters["solved"] = calls ? static_cast<double>(solved) / calls : 0.0;
  state.SetLabel(robot.robot().name());
}

// IK to targets near the nominal stance, as a planner asks during a step (small moves).
void BM_FootIkNearStance(benchmark::State& state) {
  const RobotKinematics& robot = Robot(static_cast<int>(state.range(0)));
  const LegKinematics& leg = robot.leg(0);
  LegWorkspace ws(leg);
  std::mt19937 rng(5);
  std::vector<Eigen::Vector3d> targets;
  const Eigen::Vector3d stance = leg.FootPosition(leg.nominal(), ws);
  for (int i = 0; i < 1024; ++i) {
    targets.push_back(stance + Eigen::Vector3d(std::uniform_real_distribution<double>(-0.1, 0.1)(rng),
                                               std::uniform_real_distribution<double>(-0.03, 0.03)(rng),
                                               std::uniform_real_distribution<double>(-0.05, 0.05)(rng)));
  }
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(leg.SolveFootIk(targets[i++ & 1023], ws).q);
  state.SetLabel(robot.robot().name());
}

}  // namespace

BENCHMARK(BM_FootFk)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KneeFk)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LinkFrames)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FootJacobian)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FootIk)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FootIkNearStance)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
