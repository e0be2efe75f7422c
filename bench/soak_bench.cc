// Soak benchmark (issue #9): the body planner's control-loop API, Update() every 3 ms of simulated
// time, for 1,000,000 cycles (about 50 minutes of robot time) over repeated traversals of the
// default stairs, as a robot that climbs the same flight again and again would run it.
//
// It reports and checks the promise "the control loop runs for days":
//  - resident memory after warm-up (the first traversal fills the bound caches) stays flat:
//    growth of VmRSS from the end of warm-up to the end <= 1% (sampled every 10,000 cycles);
//  - no stale plans in steady state: every timed cycle solves its own plan (status ok, knots
//    starting at `now`, all finite); the first cycle of each traversal (Reset(), warm-up solves,
//    no budget by design) is counted apart;
//  - the latency tail of Update(): p50, p90, p99, p99.9, p99.99 and max.
// Exit 0 when the bounds hold, 1 otherwise. Not a unit test: run it by hand (or with --cycles N).
//
// Stale cycles are split by cause: the wall-clock cycle budget (kTimeLimit or no time left for a
// solve: the machine, not the planner) and everything else (a solver failure: the planner). On a
// shared machine the first kind follows the load; --budget S sets the cycle budget (default the
// planner's 2.5 ms) so a run can separate the two.
//
//   ./soak_bench [--cycles N] [--budget S] [up|down] [forward|backward]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/crawl_planner.h"

using namespace stairplan;

namespace {

constexpr double kPeriod = 0.003;  // [s], 333 Hz (seed 000 [0033])

// Resident set size from /proc/self/status [kB]; 0 when unavailable.
long ResidentKb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  }
  return 0;
}

double Percentile(std::vector<float>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

int main(int argc, char** argv) {
  long cycles = 1000000;
  StairSpec spec;
  Facing facing = Facing::kForward;
  BodyPlannerSettings settings;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--budget") == 0 && i + 1 < argc) settings.cycle_budget_s = std::atof(argv[++i]);
    if (std::strcmp(argv[i], "--cycles") == 0 && i + 1 < argc) cycles = std::atol(argv[++i]);
    if (std::strcmp(argv[i], "down") == 0) spec.direction = TravelDirection::kDown;
    if (std::strcmp(argv[i], "backward") == 0) facing = Facing::kBackward;
  }
  if (cycles < 1) {
    std::fprintf(stderr, "soak_bench: --cycles must be a positive count\n");
    return 2;
  }
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, facing);
  const RobotModel& robot = BuiltinRobot();
  const Plan footsteps = PlanCrawlFootholds(robot, stairs, map);
  if (footsteps.status != PlanStatus::kOk) {
    std::printf("crawl plan infeasible: %s\n", footsteps.status_reason.c_str());
    return 3;
  }
  BodyPlanner planner(robot, stairs, map, footsteps, settings);
  const double end = planner.schedule().end_time();

  // Sized and written (zero-filled) before the baseline, so the measurement itself does not grow
  // the resident set: reserve() alone would leave the pages to be touched during the soak.
  std::vector<float> latency_us(static_cast<std::size_t>(cycles), 0.0f);
  std::size_t timed = 0;
  std::vector<long> rss_samples_kb(static_cast<std::size_t>(cycles / 10000 + 2), 0);
  std::size_t samples = 0;

  long warmup_cycles = 0, traversals = 0, restart_cycles = 0;
  long stale = 0, stale_budget = 0, infeasible = 0, not_fresh = 0, non_finite = 0;
  long rss_baseline_kb = 0;
  bool warm = false;
  BodyState state = planner.StartState();
  double now = 0.0;
  const auto wall0 = std::chrono::steady_clock::now();
  for (long cycle = 0; cycle < cycles; ++cycle) {
    if (now > end) {  // the flight is done: start it again, as a robot climbing it again would
      if (!warm) {
        warm = true;
        warmup_cycles = cycle;
        rss_baseline_kb = ResidentKb();
      }
      ++traversals;
      planner.Reset();
      state = planner.StartState();
      now = 0.0;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
    const float us = std::chrono::duration<float, std::micro>(std::chrono::steady_clock::now() - t0).count();
    if (warm) {
      if (now == 0.0) {
        ++restart_cycles;  // Reset()'s warm-up solves: no budget by design
      } else {
        latency_us[timed++] = us;
        if (out.status == BodyPlanStatus::kStale) {
          const bool budget = out.solves == 0 || out.solve_status == optim::SolveStatus::kTimeLimit;
          (budget ? stale_budget : stale) += 1;
        }
        infeasible += out.status == BodyPlanStatus::kInfeasible ? 1 : 0;
        not_fresh += std::abs(out.knots[0].t - now) > 1e-9 ? 1 : 0;
        bool finite = true;
        for (const BodyState& k : out.knots) finite = finite && std::isfinite(k.z) && std::isfinite(k.pitch) && std::isfinite(k.com_shift);
        non_finite += finite ? 0 : 1;
      }
      if (cycle % 10000 == 0 && samples + 1 < rss_samples_kb.size()) rss_samples_kb[samples++] = ResidentKb();
    }
    state = planner.Interpolate(now + kPeriod);  // the robot tracks the plan perfectly
    now += kPeriod;
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const long rss_end_kb = ResidentKb();
  rss_samples_kb[samples++] = rss_end_kb;
  const long rss_max_kb = *std::max_element(rss_samples_kb.begin(), rss_samples_kb.begin() + static_cast<std::ptrdiff_t>(samples));
  const double growth = rss_baseline_kb > 0 ? static_cast<double>(rss_max_kb - rss_baseline_kb) / static_cast<double>(rss_baseline_kb) : 0.0;
  latency_us.resize(timed);

  std::printf("soak: %s, %s %s, %ld cycles at %.0f Hz (%.1f min of robot time) in %.1f s wall\n", robot.name().c_str(),
              ToString(stairs.direction()), ToString(facing), cycles, 1.0 / kPeriod, static_cast<double>(cycles) * kPeriod / 60.0, wall_s);
  std::printf("  warm-up: the first traversal, %ld cycles (%.2f s of robot time per traversal); then %ld more traversals\n",
              warmup_cycles, end, traversals);
  std::printf("  resident memory: %ld kB after warm-up, %ld kB max after, %ld kB at the end: growth %.3f%% (bound 1%%)\n",
              rss_baseline_kb, rss_max_kb, rss_end_kb, 100.0 * growth);
  std::printf("  steady-state cycles: %zu timed, %ld traversal restarts (Reset warm-up, not timed)\n", timed, restart_cycles);
  std::printf("  cycle budget %.2f ms; stale from a solver failure: %ld; stale from the wall-clock budget: %ld (%.4f%%)\n",
              settings.cycle_budget_s * 1e3, stale, stale_budget, timed > 0 ? 100.0 * static_cast<double>(stale_budget) / static_cast<double>(timed) : 0.0);
  std::printf("  knots not starting now: %ld, non-finite outputs: %ld, infeasible: %ld\n", not_fresh, non_finite, infeasible);
  const double p50 = Percentile(latency_us, 0.5), p90 = Percentile(latency_us, 0.9), p99 = Percentile(latency_us, 0.99),
               p999 = Percentile(latency_us, 0.999), p9999 = Percentile(latency_us, 0.9999), pmax = Percentile(latency_us, 1.0);
  std::printf("  Update latency [us]: p50 %.1f  p90 %.1f  p99 %.1f  p99.9 %.1f  p99.99 %.1f  max %.1f\n", p50, p90, p99, p999,
              p9999, pmax);
  const bool ok = warm && growth <= 0.01 && stale == 0 && not_fresh == 0 && non_finite == 0;
  std::printf("  %s\n", ok ? "PASS: memory flat, no stale plans" : "FAIL: see above");
  return ok ? 0 : 1;
}
