// Perception throughput: a 100k-point camera cloud of the default stairs to a height map (with
// gaps filled), to the fitted stairs, to the constrained map; and 10k footfalls to staircases.
// Each stage is timed on its own and the whole chain once more.
#include <vector>

#include <benchmark/benchmark.h>

#include "stairplan/perception/depth_sensor.h"
#include "stairplan/perception/footfall_stairs.h"
#include "stairplan/perception/footfall_walk.h"
#include "stairplan/perception/stair_perception.h"

namespace {

using namespace stairplan;

// 100k points: a 600 x 450 camera on the bottom landing keeps ~40% of its rays.
const PointCloud& Cloud() {
  static const PointCloud cloud = [] {
    SensorPose pose;
    pose.position = Eigen::Vector3d(-0.8, 0.0, 0.5);
    pose.pitch = -0.08;
    PinholeCamera camera;
    camera.width_px = 600;
    camera.height_px = 450;
    PointCloud c = TransformCloud(ScanStairs(Staircase(StairSpec{}), camera, pose), 0.3, Eigen::Vector3d(1.0, 2.0, 0.0));
    if (c.points.size() > 100000) c.points.resize(100000);
    return c;
  }();
  return cloud;
}

// 10k footfalls: the two-up-two-down loop of seed 001 [0047] repeated side by side.
const std::vector<Footfall>& Footfalls() {
  static const std::vector<Footfall> footfalls = [] {
    std::vector<Footfall> all;
    for (int copy = 0; all.size() < 10000; ++copy) {
      const auto flight = [&](int steps, double rise, double run, TravelDirection d, Eigen::Vector3d o, double yaw) {
        StairSpec s;
        s.steps = steps;
        s.rise = rise;
        s.run = run;
        s.width = 1.2;
        s.direction = d;
        PlacedFlight f;
        f.stairs = Staircase(s);
        f.origin_W = o + Eigen::Vector3d(10.0 * copy, 0.0, 0.0);
        f.yaw = yaw;
        return f;
      };
      FootfallWalkSettings walk;
      walk.seed = static_cast<std::uint32_t>(copy + 1);
      const auto one = WalkFootfalls({flight(6, 0.17, 0.28, TravelDirection::kUp, {0, 0, 0}, 0.0),
                                      flight(5, 0.15, 0.30, TravelDirection::kUp, {3.6, 1.5, 1.02}, 0.5 * M_PI),
                                      flight(6, 0.16, 0.26, TravelDirection::kDown, {2.0, 4.5, 0.81}, M_PI),
                                      flight(5, 0.162, 0.29, TravelDirection::kDown, {-1.0, 3.6, 0.0}, -0.5 * M_PI)},
                                     walk);
      for (Footfall f : one) {
        f.t += 100.0 * copy;
        all.push_back(f);
      }
    }
    all.resize(10000);
    return all;
  }();
  return footfalls;
}

void BM_CloudToHeightMap(benchmark::State& state) {
  const PointCloud& cloud = Cloud();
  for (auto _ : state) {
    HeightMap map = HeightMap::FromCloud(cloud);
    benchmark::DoNotOptimize(map);
  }
  state.counters["points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_CloudToHeightMap)->Unit(benchmark::kMillisecond);

void BM_FillGaps(benchmark::State& state) {
  const HeightMap raw = HeightMap::FromCloud(Cloud());
  for (auto _ : state) {
    HeightMap map = raw;
    benchmark::DoNotOptimize(FillGaps(map));
  }
  state.counters["cells"] = static_cast<double>(raw.nx() * raw.ny());
}
BENCHMARK(BM_FillGaps)->Unit(benchmark::kMillisecond);

void BM_FitStairs(benchmark::State& state) {
  const PointCloud& cloud = Cloud();
  for (auto _ : state) benchmark::DoNotOptimize(FitStairs(cloud));
}
BENCHMARK(BM_FitStairs)->Unit(benchmark::kMillisecond);

void BM_HeightMapToConstrainedMap(benchmark::State& state) {
  HeightMap map = HeightMap::FromCloud(Cloud());
  FillGaps(map);
  const StairFit fit = FitStairs(Cloud());
  if (!fit.found) {
    state.SkipWithError("the benchmark cloud is not seen as stairs");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(ConstrainedMapFromHeightMap(map, fit.model));
}
BENCHMARK(BM_HeightMapToConstrainedMap)->Unit(benchmark::kMillisecond);

void BM_CloudToConstrainedMap(benchmark::State& state) {
  const PointCloud& cloud = Cloud();
  for (auto _ : state) benchmark::DoNotOptimize(PerceiveStairs(cloud));
  state.counters["points"] = static_cast<double>(cloud.size());
}
BENCHMARK(BM_CloudToConstrainedMap)->Unit(benchmark::kMillisecond);

void BM_FootfallsToStaircases(benchmark::State& state) {
  const std::vector<Footfall>& footfalls = Footfalls();
  std::size_t found = 0;
  for (auto _ : state) {
    const auto stairs = StairsFromFootfalls(footfalls);
    found = stairs.size();
    benchmark::DoNotOptimize(stairs);
  }
  state.counters["footfalls"] = static_cast<double>(footfalls.size());
  state.counters["staircases"] = static_cast<double>(found);
}
BENCHMARK(BM_FootfallsToStaircases)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
