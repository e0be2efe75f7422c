// Clearance per call: one box-box signed distance (GJK-indep), one leg's clearance to the default
// stairs (all its shapes against all stair solids, pruned), the body's, a contralateral pair, and
// a whole stance check (four IKs, four leg clearances, two leg pairs, the body).
#include <benchmark/benchmark.h>
#include <fcl/geometry/shape/box.h>

#include "stairplan/collision/signed_distance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/builtin_robot.h"

namespace {

using namespace stairplan;

struct Scene {
  StanceChecker checker{BuiltinRobot(), Staircase(StairSpec{})};
  BodyPose body;
  std::array<Eigen::Vector3d, 4> contacts;
  std::array<Eigen::Vector3d, 4> q;

  Scene() {
    // Standing across the first riser: front feet on tread 1, hind feet on the landing.
    body.position_W = {-0.05, 0.0, 0.55};
    body.pitch = -0.15;
    for (int l = 0; l < 4; ++l) {
      const auto& leg = checker.kinematics().leg(l);
      const Eigen::Vector3d foot = body.ToIsometry() * leg.FootPosition(leg.nominal(), checker.workspace().leg(l));
      const double x = foot.x() > 0.0 ? 0.12 : foot.x();
      contacts[static_cast<std::size_t>(l)] = {x, foot.y(), x > 0.0 ? 0.17 : 0.0};
    }
    const StanceResult r = checker.Check(body, contacts);
    for (int l = 0; l < 4; ++l) q[static_cast<std::size_t>(l)] = r.legs[static_cast<std::size_t>(l)].ik.q;
  }
};

Scene& TheScene() {
  static Scene scene;
  return scene;
}

void BM_BoxBoxSignedDistance(benchmark::State& state) {
  const fcl::Boxd a(0.05, 0.04, 0.26), b(0.27, 1.0, 0.67);
  Eigen::Isometry3d ta = Eigen::Isometry3d::Identity(), tb = Eigen::Isometry3d::Identity();
  ta.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ta.translation() = Eigen::Vector3d(0.1, 0.0, 0.32);
  tb.translation() = Eigen::Vector3d(0.135, 0.0, -0.165);
  for (auto _ : state) benchmark::DoNotOptimize(SignedDistance(a, ta, b, tb).distance);
}

void BM_LegStairClearance(benchmark::State& state) {
  Scene& s = TheScene();
  const int leg = static_cast<int>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(LegStairClearance(s.checker.kinematics(), s.checker.collision_model(), s.checker.stairs(),
                                               leg, s.q[static_cast<std::size_t>(leg)], s.body, s.checker.workspace())
                                 .distance);
  }
  state.SetLabel(s.checker.kinematics().leg(leg).name());
}

void BM_BodyStairClearance(benchmark::State& state) {
  Scene& s = TheScene();
  for (auto _ : state) benchmark::DoNotOptimize(BodyStairClearance(s.checker.collision_model(), s.checker.stairs(), s.body).distance);
}

void BM_ContralateralClearance(benchmark::State& state) {
  Scene& s = TheScene();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        LegLegClearance(s.checker.kinematics(), s.checker.collision_model(), 0, s.q[0], 1, s.q[1], s.checker.workspace()).distance);
  }
}

void BM_StanceCheck(benchmark::State& state) {
  Scene& s = TheScene();
  for (auto _ : state) benchmark::DoNotOptimize(s.checker.Check(s.body, s.contacts).min_clearance);
}

}  // namespace

BENCHMARK(BM_BoxBoxSignedDistance)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LegStairClearance)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BodyStairClearance)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContralateralClearance)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StanceCheck)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
