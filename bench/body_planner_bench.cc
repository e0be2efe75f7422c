// The body planner's numbers: Update() latency percentiles over 10,000+ control cycles at 333 Hz,
// the per-cycle QP through our active-set solver against Ipopt on the same program, and the exact
// NLP's solve time cold (from the QP plan) and warm (from its own previous solution).
//
//   ./body_planner_bench                  (counters: p50_us, p99_us, max_us, ratio, ...)
//
// The latencies are wall-clock; *_cpu_us are the same cycles' thread CPU time, which leaves out
// the time other processes held the core (on a shared 2-core machine the wall-clock tail is
// mostly that when other builds run: compare the two before blaming the planner).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>
#include <vector>

#include "kinematics/builtin_robot.h"
#include "planning/body/body_nlp.h"
#include "planning/body/body_planner.h"
#include "planning/crawl_planner.h"
#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/ipopt_solver.h"

using namespace stairplan;

namespace {

constexpr double kPeriod = 0.003;

double ThreadCpuMicros() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

struct Fixture {
  Staircase stairs{StairSpec{}};
  ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  Plan footsteps = PlanCrawl(BuiltinRobot(), stairs, map);
  std::unique_ptr<BodyPlanner> planner;
  Fixture() {
    BodyPlannerSettings settings;
    settings.cycle_budget_s = 1.0;  // measure every solve (the budget is the loop's business)
    planner = std::make_unique<BodyPlanner>(BuiltinRobot(), stairs, map, footsteps, settings);
    Traverse(nullptr);  // fills the bound caches
  }
  // One traversal at 333 Hz with the state advanced along the plan; latencies of the cycles
  // (wall-clock and thread CPU time).
  void Traverse(std::vector<double>* latency_us, std::vector<double>* cpu_us = nullptr) {
    planner->Reset();
    BodyState state = planner->StartState();
    for (double now = 0.0; now <= planner->schedule().end_time(); now += kPeriod) {
      const double c0 = ThreadCpuMicros();
      const auto t0 = std::chrono::steady_clock::now();
      const BodyPlannerOutput& out = planner->Update(state, BodyCommand{}, now);
      const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = ThreadCpuMicros() - c0;
      if (latency_us != nullptr && out.solves == 1) latency_us->push_back(us);
      if (cpu_us != nullptr && out.solves == 1) cpu_us->push_back(cpu);
      state = planner->Interpolate(now + kPeriod);
    }
  }
  // Moves the planner to time t on the flight (warm) and returns it.
  double MoveTo(double t) {
    planner->Reset();
    BodyState state = planner->StartState();
    double now = 0.0;
    for (; now < t; now += kPeriod) {
      planner->Update(state, BodyCommand{}, now);
      state = planner->Interpolate(now + kPeriod);
    }
    planner->Update(state, BodyCommand{}, now);
    return now;
  }
};

Fixture& Shared() {
  static Fixture fixture;
  return fixture;
}

double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

void BM_UpdateLatency(benchmark::State& state) {
  Fixture& f = Shared();
  std::vector<double> latency, cpu;
  for (auto _ : state) {
    latency.clear();
    cpu.clear();
    while (latency.size() < 10000) f.Traverse(&latency, &cpu);
  }
  state.counters["cycles"] = static_cast<double>(latency.size());
  state.counters["p50_us"] = Percentile(latency, 0.5);
  state.counters["p99_us"] = Percentile(latency, 0.99);
  state.counters["max_us"] = Percentile(latency, 1.0);
  state.counters["p50_cpu_us"] = Percentile(cpu, 0.5);
  state.counters["p99_cpu_us"] = Percentile(cpu, 0.99);
  state.counters["max_cpu_us"] = Percentile(cpu, 1.0);
}
BENCHMARK(BM_UpdateLatency)->Iterations(1)->Unit(benchmark::kMillisecond);

// The QP of one cycle on the flight: our warm re-solve against Ipopt from scratch.
void BM_QpActiveSetVsIpopt(benchmark::State& state) {
  Fixture& f = Shared();
  f.MoveTo(3.0);
  const optim::Program& program = f.planner->qp().program();
  optim::ActiveSetQpSolver ours;
  optim::SolveResult result;
  ours.Solve(program, &result);  // factorise once, as the planner's solver has
  double ours_us = 0.0, ipopt_us = 0.0;
  int n = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    ours.Solve(program, &result);
    ours_us += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    optim::IpoptSolver ipopt;
    optim::SolveResult r;
    t0 = std::chrono::steady_clock::now();
    ipopt.Solve(program, &r);
    ipopt_us += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(r.x.data());
    ++n;
  }
  state.counters["active_set_us"] = ours_us / n;
  state.counters["ipopt_us"] = ipopt_us / n;
  state.counters["ratio"] = ipopt_us / ours_us;
}
BENCHMARK(BM_QpActiveSetVsIpopt)->Iterations(20)->Unit(benchmark::kMillisecond);

// The exact NLP over the horizon: cold from the QP plan, warm from its previous solution one
// cycle earlier (shifted by a knot). Issue 6 asks for warm_ms <= 10 (Ipopt); objective_gap and the
// bound distances (>= -1e-3 mm: no bound broken) say the solutions stay what they were.
void BM_NlpColdWarm(benchmark::State& state) {
  Fixture& f = Shared();
  BodyNlpSettings settings;
  settings.solver = state.range(0) == 0 ? "ipopt" : "nlopt";
  double cold_ms = 0.0, warm_ms = 0.0, cold_cpu_ms = 0.0, warm_cpu_ms = 0.0, cold_iterations = 0.0, warm_iterations = 0.0;
  double own_ms = 0.0, own_cpu_ms = 0.0, own_iterations = 0.0;
  int n = 0;
  for (auto _ : state) {
    const double now = f.MoveTo(3.0);
    std::vector<BodyState> first, second;
    const BodyNlpWindow cold = SolveBodyNlpFrom(*f.planner, settings, now, f.planner->output().knots, &first);
    // Next knot: the previous solution shifted by one knot, its last knot repeated.
    const double next = now + f.planner->settings().knot_dt;
    f.planner->Update(f.planner->Interpolate(next), BodyCommand{}, next);
    std::vector<BodyState> guess(first.begin() + 1, first.end());
    guess.push_back(first.back());
    guess.front() = f.planner->output().knots.front();
    const BodyNlpWindow warm = SolveBodyNlpFrom(*f.planner, settings, next, guess, &second);
    // The same with knot 0 where the NLP's own plan put it (a loop that follows the NLP rather
    // than the QP): what the QP state's mismatch with the NLP plan costs the warm start.
    guess.front() = first[1];
    std::vector<BodyState> third;
    const BodyNlpWindow own = SolveBodyNlpFrom(*f.planner, settings, next, guess, &third);
    own_ms += own.solve_ms;
    own_cpu_ms += own.solve_cpu_ms;
    own_iterations += own.iterations;
    cold_ms += cold.solve_ms;
    warm_ms += warm.solve_ms;
    cold_cpu_ms += cold.solve_cpu_ms;
    warm_cpu_ms += warm.solve_cpu_ms;
    cold_iterations += cold.iterations;
    warm_iterations += warm.iterations;
    ++n;
    state.counters["objective_gap"] = (cold.qp_objective - cold.nlp_objective) / cold.qp_objective;
    state.counters["qp_bound_distance_mm"] = 1e3 * cold.qp_bound_distance;
    state.counters["nlp_bound_distance_mm"] = 1e3 * cold.nlp_bound_distance;
    state.counters["warm_objective_gap"] = (warm.qp_objective - warm.nlp_objective) / warm.qp_objective;
    state.counters["warm_nlp_bound_distance_mm"] = 1e3 * warm.nlp_bound_distance;
    state.counters["warm_solved"] = warm.status == optim::SolveStatus::kSolved ? 1.0 : 0.0;
  }
  state.counters["cold_ms"] = cold_ms / n;
  state.counters["warm_ms"] = warm_ms / n;
  // CPU time of the same solves: on a loaded machine the wall clock also counts other processes.
  state.counters["cold_cpu_ms"] = cold_cpu_ms / n;
  state.counters["warm_cpu_ms"] = warm_cpu_ms / n;
  state.counters["cold_iterations"] = cold_iterations / n;  // Ipopt iterations, NLopt evaluations
  state.counters["warm_iterations"] = warm_iterations / n;
  state.counters["warm_own_state_ms"] = own_ms / n;
  state.counters["warm_own_state_cpu_ms"] = own_cpu_ms / n;
  state.counters["warm_own_state_iterations"] = own_iterations / n;
}
BENCHMARK(BM_NlpColdWarm)->Arg(0)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
