// The validator's dynamic check: the per-instant contact-force QP (planning/validation/
// contact_wrench_qp.h) over a crawl's sequence of instants, warm-started from the previous
// instant as the validator runs it, against the same sequence solved cold (like with like); an
// identical re-solve is its own regime. Then what the check adds to validating the default climb:
// the whole validation with the dynamic check and without it, per checked instant.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "kinematics/builtin_robot.h"
#include "planning/plan_pipeline.h"
#include "planning/validation/contact_wrench_qp.h"
#include "planning/validation/traversal_validator.h"

namespace {

using namespace stairplan;

struct WrenchInstant {
  std::array<ContactFoot, 4> feet;
  Eigen::Vector3d com_W, force_W, moment_W;
};

// A crawl across a riser: front feet a tread up, one foot in swing in three instants of four,
// the COM shifting over the support, the weight plus accelerations of up to 3 m/s^2.
std::vector<WrenchInstant> CrawlSequence() {
  constexpr double kMass = 27.6;
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<WrenchInstant> sequence;
  const double xs[] = {0.135, 0.135, -0.135, -0.135}, ys[] = {0.18, -0.18, 0.18, -0.18};
  for (int k = 0; k < 2000; ++k) {
    WrenchInstant w;
    const int swing = (k / 25) % 5;  // 4: all feet down
    for (int i = 0; i < 4; ++i) {
      ContactFoot& foot = w.feet[static_cast<std::size_t>(i)];
      foot.stance = i != swing;
      foot.position_W = {xs[i], ys[i], xs[i] > 0.0 ? 0.17 : 0.0};
      foot.torque_map << 0.0, -0.3, 0.0, 0.3, 0.0, 0.05, 0.15, 0.0, 0.2;  // a bent leg's -J^T, roughly
      foot.effort = Eigen::Vector3d::Constant(40.0);
    }
    const double shift = swing < 4 ? 0.04 : 0.0;
    w.com_W = {-shift * (swing < 2 ? 1 : -1) + 0.01 * unit(rng), shift * (swing % 2 == 0 ? -1 : 1), 0.45};
    w.force_W = kMass * Eigen::Vector3d(3.0 * unit(rng), 3.0 * unit(rng), 9.81 + 3.0 * unit(rng));
    w.moment_W = Eigen::Vector3d(unit(rng), unit(rng), 0.2 * unit(rng));
    sequence.push_back(w);
  }
  return sequence;
}

// Times each solve of the sequence; p50 and p99 as counters.
template <typename BeforeSolve>
void TimeSequence(benchmark::State& state, BeforeSolve before, bool same_instant) {
  const std::vector<WrenchInstant> sequence = CrawlSequence();
  ContactWrenchQp qp;
  std::vector<double> us;
  us.reserve(1 << 20);
  std::size_t i = 0;
  double residual = 0.0;
  for (auto _ : state) {
    const WrenchInstant& w = sequence[same_instant ? 0 : i];
    before(qp);
    const auto t0 = std::chrono::steady_clock::now();
    residual += qp.Solve(w.feet, w.com_W, w.force_W, w.moment_W).residual;
    const auto t1 = std::chrono::steady_clock::now();
    if (us.size() < us.capacity()) us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    i = (i + 1) % sequence.size();
  }
  benchmark::DoNotOptimize(residual);
  std::sort(us.begin(), us.end());
  const auto at = [&](double q) { return us.empty() ? 0.0 : us[static_cast<std::size_t>(q * static_cast<double>(us.size() - 1))]; };
  state.counters["p50_us"] = at(0.50);
  state.counters["p99_us"] = at(0.99);
}

void BM_ContactWrenchWarmSequence(benchmark::State& state) {
  TimeSequence(state, [](ContactWrenchQp&) {}, false);
}
BENCHMARK(BM_ContactWrenchWarmSequence)->Unit(benchmark::kMicrosecond);

void BM_ContactWrenchColdSequence(benchmark::State& state) {
  TimeSequence(state, [](ContactWrenchQp& qp) { qp.ResetWarmStart(); }, false);
}
BENCHMARK(BM_ContactWrenchColdSequence)->Unit(benchmark::kMicrosecond);

void BM_ContactWrenchIdenticalResolve(benchmark::State& state) {
  TimeSequence(state, [](ContactWrenchQp&) {}, true);
}
BENCHMARK(BM_ContactWrenchIdenticalResolve)->Unit(benchmark::kMicrosecond);

struct DefaultClimb {
  Staircase stairs{StairSpec{}};
  PipelineResult result;
  DefaultClimb() {
    PipelineOptions options;
    options.validate = false;
    result = RunPipeline(BuiltinRobot(), stairs, options);
  }
};

const DefaultClimb& TheClimb() {
  static const DefaultClimb climb;
  return climb;
}

// A whole validation of the default climb's plan, per checked instant, with or without the check.
void BM_ValidateDefaultClimb(benchmark::State& state) {
  const DefaultClimb& climb = TheClimb();
  ValidationSettings settings;
  settings.check_dynamics = state.range(0) != 0;
  TraversalValidator validator(BuiltinRobot(), climb.stairs, climb.result.map, settings);
  int samples = 0;
  for (auto _ : state) samples = validator.Validate(climb.result.plan).samples;
  state.counters["instants"] = samples;
  state.counters["instants_per_s"] = benchmark::Counter(
      static_cast<double>(samples) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["dynamics"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_ValidateDefaultClimb)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
