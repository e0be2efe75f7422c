// The body planner's numbers: Update() latency percentiles over 10,000+ control cycles at 333 Hz
// (and, with leg rows, over one traversal at 333 Hz and one at the knot spacing),
// the per-cycle QP through our active-set solver, Ipopt and CLP on the same programs, cold and
// warm sequence (never one regime against the other), and the exact
// NLP's solve time cold (from the QP plan) and warm (each cycle from the previous cycle's
// solution and multipliers, shifted a knot).
//
//   ./body_planner_bench                  (counters: p50_us, p99_us, max_us, mean_cpu_us, ...)
//   STAIRPLAN_BENCH_SMOKE=1 ./body_planner_bench   (ctest's smoke run: one solved cycle each, a few QPs)
//
// Every latency traversal starts from a new planner: its bound-grid nodes (KinematicBodyBounds)
// and carried leg rows (KnotRowCache) are empty, as on a robot starting the flight, so the cycles
// that fill them are measured (nodes_computed, cycles_with_fills; *_no_fills: the other cycles).
// The latencies are wall-clock; *_cpu_us are the same cycles' thread CPU time, which leaves out
// the time other processes held the core (on a shared 2-core machine the wall-clock tail is
// mostly that when other builds run: compare the two before blaming the planner).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/body_nlp/body_nlp.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/crawl_planner.h"
#include "stairplan/solvers/clp_solver.h"
#include "stairplan/solvers/qp_benchmark.h"
#include "stairplan/solvers/make_solver.h"

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
  Plan footsteps = PlanCrawlFootholds(BuiltinRobot(), stairs, map);
  BodyPlannerSettings settings;
  std::unique_ptr<BodyPlanner> planner;
  double period = kPeriod;  // of the control loop [s]
  explicit Fixture(BodyPlannerSettings planner_settings = {}, double loop_period = kPeriod)
      : settings(planner_settings), period(loop_period) {
    settings.cycle_budget_s = 1.0;  // measure every solve (the budget is the loop's business)
    Rebuild();
  }
  // A new planner: empty bound and row caches, as a robot has them when it starts a flight.
  void Rebuild() { planner = std::make_unique<BodyPlanner>(BuiltinRobot(), stairs, map, footsteps, settings); }
  int NodesComputed() {
    const auto* bounds = dynamic_cast<const KinematicBodyBounds*>(&planner->bounds());
    return bounds == nullptr ? 0 : bounds->reach_nodes_computed() + bounds->clearance_nodes_computed();
  }
  static bool Smoke() { return std::getenv("STAIRPLAN_BENCH_SMOKE") != nullptr; }
  // Per solved cycle (out.solves == 1; the warm-up cycle is not one): wall-clock and thread CPU
  // time, and what the cycle did.
  struct Cycles {
    std::vector<double> latency_us, cpu_us, bounds_us, solve_us, iterations, linearised, reused;
    // Bound-cache nodes (KinematicBodyBounds' grid) the cycle computed, and the CPU time of the
    // cycles that computed none.
    std::vector<double> nodes, cpu_no_fill_us, bounds_no_fill_us, solve_no_fill_us;
    std::size_t size() const { return latency_us.size(); }
    void clear() {
      for (std::vector<double>* v : {&latency_us, &cpu_us, &bounds_us, &solve_us, &iterations, &linearised, &reused, &nodes,
                                     &cpu_no_fill_us, &bounds_no_fill_us, &solve_no_fill_us}) {
        v->clear();
      }
    }
  };
  // One traversal from a new planner (empty caches) with the state advanced along the plan.
  void Traverse(Cycles* cycles) {
    const std::size_t limit = Smoke() ? 1 : static_cast<std::size_t>(-1);  // the smoke run: one solved cycle
    Rebuild();
    BodyState state = planner->StartState();
    const double end = planner->schedule().end_time();
    for (int cycle = 0; cycle * period <= end && cycles->size() < limit; ++cycle) {
      const double now = cycle * period;  // not a running sum: the knots' instants recur exactly
      const int nodes0 = NodesComputed();
      const double c0 = ThreadCpuMicros();
      const auto t0 = std::chrono::steady_clock::now();
      const BodyPlannerOutput& out = planner->Update(state, BodyCommand{}, now);
      const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = ThreadCpuMicros() - c0;
      if (out.solves == 1) {
        cycles->latency_us.push_back(us);
        cycles->cpu_us.push_back(cpu);
        cycles->bounds_us.push_back(out.timings.bounds_us);
        cycles->solve_us.push_back(out.timings.solve_us);
        cycles->iterations.push_back(out.iterations);
        cycles->linearised.push_back(out.linearised_knots);
        cycles->reused.push_back(out.reused_knots);
        const int nodes = NodesComputed() - nodes0;
        cycles->nodes.push_back(nodes);
        if (nodes == 0) {
          cycles->cpu_no_fill_us.push_back(cpu);
          cycles->bounds_no_fill_us.push_back(out.timings.bounds_us);
          cycles->solve_no_fill_us.push_back(out.timings.solve_us);
        }
      }
      state = planner->Interpolate(now + period);
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

// Update's latency percentiles over `wanted` cycles (at least one traversal) of `f`.
void ReportLatency(benchmark::State& state, Fixture& f, std::size_t wanted) {
  // The smoke run's traversal stops after one solved cycle: asking for more would never end.
  const std::size_t wanted_cycles = Fixture::Smoke() ? 1 : wanted;
  Fixture::Cycles c;
  for (auto _ : state) {
    c.clear();
    while (c.size() < wanted_cycles) f.Traverse(&c);
  }
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return sum / static_cast<double>(std::max<std::size_t>(1, v.size()));
  };
  state.counters["cycles"] = static_cast<double>(c.size());
  state.counters["p50_us"] = Percentile(c.latency_us, 0.5);
  state.counters["p99_us"] = Percentile(c.latency_us, 0.99);
  state.counters["max_us"] = Percentile(c.latency_us, 1.0);
  state.counters["p50_cpu_us"] = Percentile(c.cpu_us, 0.5);
  state.counters["p99_cpu_us"] = Percentile(c.cpu_us, 0.99);
  state.counters["max_cpu_us"] = Percentile(c.cpu_us, 1.0);
  // Where a cycle's time goes (wall-clock): the rows and bounds, and the QP.
  state.counters["p99_bounds_us"] = Percentile(c.bounds_us, 0.99);
  state.counters["p99_solve_us"] = Percentile(c.solve_us, 0.99);
  state.counters["mean_iterations"] = mean(c.iterations);
  state.counters["max_iterations"] = Percentile(c.iterations, 1.0);
  state.counters["mean_linearised_knots"] = mean(c.linearised);
  state.counters["mean_reused_knots"] = mean(c.reused);
  state.counters["nodes_computed"] = mean(c.nodes) * static_cast<double>(c.size());
  state.counters["cycles_with_fills"] = static_cast<double>(c.size() - c.cpu_no_fill_us.size());
  if (!c.cpu_no_fill_us.empty()) {
    state.counters["p50_cpu_us_no_fills"] = Percentile(c.cpu_no_fill_us, 0.5);
    state.counters["p99_cpu_us_no_fills"] = Percentile(c.cpu_no_fill_us, 0.99);
    state.counters["p99_bounds_us_no_fills"] = Percentile(c.bounds_no_fill_us, 0.99);
    state.counters["p99_solve_us_no_fills"] = Percentile(c.solve_no_fill_us, 0.99);
  }
}

void BM_UpdateLatency(benchmark::State& state) { ReportLatency(state, Shared(), 10000); }
BENCHMARK(BM_UpdateLatency)->Iterations(1)->Unit(benchmark::kMillisecond);

// With leg rows (KDL joint and extension rows, FCL clearances, the exact COM; stability margin
// 0.03 m) over one traversal: Arg 0 at 333 Hz, where every cycle falls between the last one's
// knots and linearises all of them; Arg 1 at the knot spacing (40 Hz), where the rows of a knot
// the last cycle linearised near its centre are carried over (KnotRowCache). Warm sequences
// both: each cycle from the last one's plan and active set.
void BM_UpdateLatencyLegRows(benchmark::State& state) {
  BodyPlannerSettings settings;
  settings.stance_rows = true;
  settings.stability_margin = 0.03;
  const bool at_knots = state.range(0) == 1;
  static std::unique_ptr<Fixture> fixtures[2];  // one per cycle period, built on first use
  std::unique_ptr<Fixture>& fixture = fixtures[at_knots ? 1 : 0];
  if (!fixture) fixture = std::make_unique<Fixture>(settings, at_knots ? settings.knot_dt : kPeriod);
  ReportLatency(state, *fixture, 1);
  state.SetLabel(at_knots ? "leg rows, cycle = knot spacing (rows carried)" : "leg rows, 333 Hz (rows linearised every cycle)");
}
BENCHMARK(BM_UpdateLatencyLegRows)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond);

// The same over one traversal with the settings `plan --body qp` plans with (LegRowBodySettings:
// 20 knots 50 ms apart, the shift boxes and trust regions that go with them), one cycle per knot.
void BM_UpdateLatencyPlanBodySettings(benchmark::State& state) {
  static std::unique_ptr<Fixture> fixture;
  const BodyPlannerSettings settings = LegRowBodySettings();
  if (!fixture) fixture = std::make_unique<Fixture>(settings, settings.knot_dt);
  ReportLatency(state, *fixture, 1);
  state.SetLabel("LegRowBodySettings (plan --body qp), cycle = knot spacing (rows carried)");
}
BENCHMARK(BM_UpdateLatencyPlanBodySettings)->Iterations(1)->Unit(benchmark::kMillisecond);

// The body QP of the planner's own cycles along the flight (the program Update() built, solved
// again by each solver beside the planner), 200 consecutive cycles from t = 2 s, in two regimes:
// cold (a fresh solver per cycle, no guess) and warm sequence (one solver, each cycle from the
// previous cycle's solution: ours and CLP from their active set or basis, Ipopt from x and its
// multipliers with warm_start_init_point). CPU time per QP; ratio_vs_active_set only within
// the regime. banded-ipm (our interior point over a band Cholesky) warm-starts by trying the
// previous cycle's active set first (one equality-constrained solve, 0 iterations when it
// holds) and runs its interior point from its own start when it does not; its label says so.
std::map<std::string, double>& ActiveSetMeans() {
  static std::map<std::string, double> means;
  return means;
}

void BM_BodyQp(benchmark::State& state, const std::string& solver, optim::SolveRegime regime) {
  Fixture& f = Shared();
  const bool smoke = std::getenv("STAIRPLAN_BENCH_SMOKE") != nullptr;
  const int cycles = smoke ? 3 : 200;
  // A reference solver that cycles (CLP's primal simplex can) gives a failed sample, not a hang.
  const double limit_s = smoke ? 1.0 : 10.0;
  std::vector<optim::QpSample> samples;
  for (auto _ : state) {
    double now = f.MoveTo(2.0);
    optim::Program program = f.planner->qp().program();
    samples = optim::MeasureSequence([solver, limit_s] { return optim::MakeSolver(solver, limit_s); }, regime, &program, cycles,
                                     [&](int k, optim::Program* p) {
                                       if (k > 0) {
                                         now += kPeriod;
                                         f.planner->Update(f.planner->Interpolate(now), BodyCommand{}, now);
                                       }
                                       *p = f.planner->qp().program();
                                     });
  }
  if (samples.empty()) return state.SkipWithError("no body QP measured");
  std::vector<double> cpu;
  double iterations = 0;
  int solved = 0;
  for (const optim::QpSample& s : samples) {
    cpu.push_back(s.cpu_us);
    iterations += s.iterations;
    solved += s.SolvedWithin(optim::kMidAccuracy) ? 1 : 0;
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, samples.size()));
  double mean = 0;
  for (double c : cpu) mean += c / n;
  state.counters["qps"] = static_cast<double>(samples.size());
  state.counters["mean_cpu_us"] = mean;
  state.counters["p50_cpu_us"] = Percentile(cpu, 0.5);
  state.counters["max_cpu_us"] = Percentile(cpu, 1.0);
  state.counters["it_per_qp"] = iterations / n;
  state.counters["solved_1e-6"] = solved;
  if (solver == "banded-ipm" && regime == optim::SolveRegime::kWarmSequence) {
    state.SetLabel("warm: the last active set's polish first, the interior point from its own start when it fails");
  }
  const std::string key(optim::ToString(regime));
  if (solver == "active-set") ActiveSetMeans()[key] = mean;
  if (solver != "active-set" && ActiveSetMeans().count(key) > 0) {
    state.counters["ratio_vs_active_set"] = mean / ActiveSetMeans()[key];
  }
}

int RegisterBodyQp() {
  std::vector<std::string> solvers = {"active-set", "banded-ipm", "ipopt"};
  if (optim::ClpSolver::IsAvailable()) solvers.push_back("clp");
  for (const optim::SolveRegime regime : {optim::SolveRegime::kCold, optim::SolveRegime::kWarmSequence}) {
    for (const std::string& solver : solvers) {
      benchmark::RegisterBenchmark(("BM_BodyQp/" + std::string(optim::ToString(regime)) + "/" + solver).c_str(),
                                   BM_BodyQp, solver, regime)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return 0;
}
const int kBodyQpRegistered = RegisterBodyQp();

// The exact NLP over the horizon as a control loop runs it: cold from the QP plan once, then
// kWarmCycles windows each one knot later, each warm-started from the window before's solution
// (SolveBodyNlpWarm: its knots and multipliers shifted by the knot, knot 0 pinned to the state).
// warm_own_state_*: the state is where the NLP's previous plan put it (its knot 1), a loop that
// follows the NLP's plan. warm_*: the state is the QP planner's (the loop follows the QP plan,
// warm_state_offset_mm off the NLP's in height or COM shift: a disturbed state). warm_primal_*:
// the same windows as warm_* through SolveBodyNlpFrom from the shifted knots alone (no
// multipliers, and its cold settings: Mehrotra's predictor-corrector, which takes 14.5 iterations
// there where the monotone barrier took 8.6, still more than with multipliers). Issue 6 asks for
// warm <= 10 ms (Ipopt). *_max_* are the slowest of the cycles; the bound distances (>= -1e-3 mm:
// no bound broken) and objective gaps say the solutions stay what they were.
constexpr int kWarmCycles = 8;

struct NlpStats {
  double ms = 0.0, cpu_ms = 0.0, iterations = 0.0, max_ms = 0.0, max_cpu_ms = 0.0, max_iterations = 0.0;
  double worst_bound_distance = 1e9;
  int solves = 0, solved = 0;
  void Add(const BodyNlpWindow& w) {
    ms += w.solve_ms;
    cpu_ms += w.solve_cpu_ms;
    iterations += w.iterations;
    max_ms = std::max(max_ms, w.solve_ms);
    max_cpu_ms = std::max(max_cpu_ms, w.solve_cpu_ms);
    max_iterations = std::max(max_iterations, static_cast<double>(w.iterations));
    worst_bound_distance = std::min(worst_bound_distance, w.nlp_bound_distance);
    ++solves;
    solved += w.status == optim::SolveStatus::kSolved ? 1 : 0;
  }
  // Wall-clock and CPU time (on a loaded machine the wall clock also counts other processes).
  void Report(benchmark::State& state, const std::string& prefix) const {
    state.counters[prefix + "_ms"] = ms / solves;
    state.counters[prefix + "_cpu_ms"] = cpu_ms / solves;
    state.counters[prefix + "_iterations"] = iterations / solves;  // Ipopt iterations, NLopt evaluations
    state.counters[prefix + "_max_ms"] = max_ms;
    state.counters[prefix + "_max_cpu_ms"] = max_cpu_ms;
    state.counters[prefix + "_max_iterations"] = max_iterations;
    state.counters[prefix + "_solved_fraction"] = static_cast<double>(solved) / solves;
    state.counters[prefix + "_nlp_bound_distance_mm"] = 1e3 * worst_bound_distance;
  }
};

void BM_NlpColdWarm(benchmark::State& state) {
  Fixture& f = Shared();
  BodyNlpSettings settings;
  settings.solver = state.range(0) == 0 ? "ipopt" : "nlopt";
  const double dt = f.planner->settings().knot_dt;
  NlpStats cold, warm, own, primal;
  double state_offset_mm = 0.0;
  for (auto _ : state) {
    double now = f.MoveTo(3.0);
    BodyNlpSolution solution;
    const BodyNlpWindow c = SolveBodyNlpFrom(*f.planner, settings, now, f.planner->output().knots, &solution);
    cold.Add(c);
    state.counters["objective_gap"] = (c.qp_objective - c.nlp_objective) / c.qp_objective;
    state.counters["qp_bound_distance_mm"] = 1e3 * c.qp_bound_distance;
    state.counters["nlp_bound_distance_mm"] = 1e3 * c.nlp_bound_distance;
    BodyNlpSolution own_solution = solution, primal_solution = solution;
    for (int cycle = 0; cycle < kWarmCycles; ++cycle) {
      const double next = now + dt;
      f.planner->Update(f.planner->Interpolate(next), BodyCommand{}, next);
      const BodyState qp_state = f.planner->output().knots.front();
      // How far the QP's state is from where the previous NLP solution put knot 1.
      state_offset_mm = std::max({state_offset_mm, 1e3 * std::abs(qp_state.z - solution.knots[1].z),
                                  1e3 * std::abs(qp_state.com_shift - solution.knots[1].com_shift)});
      warm.Add(SolveBodyNlpWarm(*f.planner, settings, next, qp_state, solution, &solution));
      own.Add(SolveBodyNlpWarm(*f.planner, settings, next, own_solution.knots[1], own_solution, &own_solution));
      const std::vector<BodyState> shifted =
          ShiftBodyNlpSolution(primal_solution, next, f.planner->settings(), qp_state).knots;
      primal.Add(SolveBodyNlpFrom(*f.planner, settings, next, shifted, &primal_solution));
      now = next;
    }
  }
  cold.Report(state, "cold");
  warm.Report(state, "warm");
  own.Report(state, "warm_own_state");
  primal.Report(state, "warm_primal");
  state.counters["warm_state_offset_mm"] = state_offset_mm;  // the largest, height or COM shift
}
BENCHMARK(BM_NlpColdWarm)->Arg(0)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
