// The active-set QP solver against Ipopt: (a) a body-planner-shaped QP (40 knots, 3 variables
// each, banded rows) re-solved per cycle, (b) the Maros-Meszaros set, (c) the Online QP
// sequences diesel and crane warm-started QP after QP. Prints the ratios at the end.
// Goals: >= 50x faster than Ipopt on (a); per-QP times on (c) near qpOASES's published 4.7 us
// (diesel) and 19 us (crane).
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <limits>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/body_qp_example.h"
#include "planning/optim/ipopt_solver.h"
#include "planning/optim/oqp_reader.h"
#include "planning/optim/qps_reader.h"

using namespace stairplan::optim;

namespace {

// Wall-clock and this thread's CPU time; the machine is shared, so CPU time is the steadier one.
struct Stamp {
  std::chrono::steady_clock::time_point wall;
  double cpu_us;
};

Stamp Now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return {std::chrono::steady_clock::now(), ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3};
}

// Accumulated solve times of one benchmark run.
struct SolveTimer {
  double wall_us = 0.0, cpu_us = 0.0;
  long solves = 0;
  Stamp start{};
  void Start() { start = Now(); }
  void Stop() {
    const Stamp end = Now();
    wall_us += std::chrono::duration<double, std::micro>(end.wall - start.wall).count();
    cpu_us += end.cpu_us - start.cpu_us;
    ++solves;
  }
};

// Mean microseconds (wall, CPU) per solve of each benchmark's last run, for the ratio table.
std::map<std::string, std::pair<double, double>>& MicrosPerSolve() {
  static std::map<std::string, std::pair<double, double>> table;
  return table;
}

void Record(benchmark::State& state, const std::string& key, const SolveTimer& t) {
  const double n = static_cast<double>(std::max(1L, t.solves));
  MicrosPerSolve()[key] = {t.wall_us / n, t.cpu_us / n};
  state.counters["us_per_qp"] = t.wall_us / n;
  state.counters["cpu_us_per_qp"] = t.cpu_us / n;
}

std::string SharedDir() { return STAIRPLAN_SHARED_DIR; }

// (a) The per-cycle problem: bounds and linear terms change every cycle.
void BodyQpActiveSet(benchmark::State& state, bool warm) {
  BodyQpExample e = MakeBodyQpExample(40);
  ActiveSetQpSettings settings;
  settings.warm_start = warm;
  ActiveSetQpSolver solver(settings);
  SolveResult result;
  solver.Solve(e.program, &result);
  int cycle = 0;
  SolveTimer timer;
  for (auto _ : state) {
    UpdateBodyQpExample(++cycle % 400, &e);
    timer.Start();
    solver.Solve(e.program, &result);
    timer.Stop();
    if (!result.solved()) state.SkipWithError("active-set solver did not solve the body QP");
  }
  Record(state, warm ? "body/active-set-warm" : "body/active-set-cold", timer);
}

void BodyQpIpopt(benchmark::State& state) {
  BodyQpExample e = MakeBodyQpExample(40);
  IpoptSolver solver;
  SolveResult result;
  int cycle = 0;
  SolveTimer timer;
  for (auto _ : state) {
    UpdateBodyQpExample(++cycle % 400, &e);
    timer.Start();
    solver.Solve(e.program, &result);
    timer.Stop();
    if (!result.solved()) state.SkipWithError("Ipopt did not solve the body QP");
  }
  Record(state, "body/ipopt", timer);
}

// (b) The Maros-Meszaros set, each problem solved from scratch (fresh solver: factorisation
// included). Time per problem is the mean over the set.
std::vector<QpsProblem>& MarosMeszaros() {
  static std::vector<QpsProblem> problems = [] {
    std::vector<QpsProblem> list;
    const std::string dir = SharedDir() + "/data/qp/maros_meszaros";
    if (!std::filesystem::is_directory(dir)) return list;
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() == ".SIF") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) list.push_back(ReadQpsFile(f));
    return list;
  }();
  return problems;
}

template <typename SolverType>
void MarosMeszarosSet(benchmark::State& state, const std::string& key) {
  const auto& problems = MarosMeszaros();
  if (problems.empty()) {
    state.SkipWithError("../shared/data/qp/maros_meszaros not found");
    return;
  }
  long solved = 0;
  SolveTimer timer;
  for (auto _ : state) {
    for (const auto& q : problems) {
      SolverType solver;
      timer.Start();
      const SolveResult r = solver.Solve(q.program);
      timer.Stop();
      solved += r.solved() ? 1 : 0;
    }
  }
  state.counters["solved"] = static_cast<double>(solved) / static_cast<double>(state.iterations());
  Record(state, key, timer);
}

void MarosMeszarosActiveSet(benchmark::State& state, const std::string& key) {
  MarosMeszarosSet<ActiveSetQpSolver>(state, key);
}

void MarosMeszarosIpopt(benchmark::State& state, const std::string& key) { MarosMeszarosSet<IpoptSolver>(state, key); }

// (c) Online QP sequences: QP k+1 warm-started from QP k.
const OqpSequence* Sequence(const std::string& name) {
  static std::map<std::string, OqpSequence> cache;
  const auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::string dir = SharedDir() + "/data/qp/online_qp/" + name;
  if (!std::filesystem::is_directory(dir)) return nullptr;
  return &cache.emplace(name, ReadOqpSequence(dir)).first->second;
}

// Solves the first `max_qps` QPs of a sequence in order, each from the previous one's state.
template <typename Solver>
void SequenceWith(benchmark::State& state, const std::string& name, const std::string& label, int max_qps) {
  const OqpSequence* s = Sequence(name);
  if (s == nullptr) {
    state.SkipWithError("../shared/data/qp/online_qp not found");
    return;
  }
  Program p = s->MakeProgram();
  Solver solver;
  SolveResult r;
  SolveTimer timer;
  for (auto _ : state) {
    for (int k = 0; k < std::min(max_qps, s->num_qps); ++k) {
      s->Apply(k, &p);
      timer.Start();
      solver.Solve(p, &r);
      timer.Stop();
    }
  }
  Record(state, name + "/" + label, timer);
}

void SequenceActiveSet(benchmark::State& state, const std::string& name) {
  SequenceWith<ActiveSetQpSolver>(state, name, "active-set", std::numeric_limits<int>::max());
}

// Ipopt has no warm start worth the name here; the first 40 QPs of the sequence suffice for a
// per-QP time.
void SequenceIpopt(benchmark::State& state, const std::string& name) { SequenceWith<IpoptSolver>(state, name, "ipopt", 40); }

void PrintRatios() {
  const auto& t = MicrosPerSolve();
  const auto line = [&](const std::string& what, const std::string& ours, const std::string& theirs, const char* note) {
    if (!t.count(ours) || !t.count(theirs)) return;
    const auto& [wall, cpu] = t.at(ours);
    const auto& [ipopt_wall, ipopt_cpu] = t.at(theirs);
    std::printf("%-34s %9.2f us (cpu %9.2f)  Ipopt %9.0f us (cpu %9.0f)  -> %6.0fx (cpu %6.0fx) %s\n", what.c_str(), wall,
                cpu, ipopt_wall, ipopt_cpu, ipopt_wall / wall, ipopt_cpu / cpu, note);
  };
  std::printf("\nper-solve times and ratios, active-set vs Ipopt (wall clock; CPU time in brackets)\n");
  line("(a) body QP, 40 knots, warm", "body/active-set-warm", "body/ipopt", "(goal >= 50x)");
  line("(a) body QP, 40 knots, cold", "body/active-set-cold", "body/ipopt", "");
  line("(b) Maros-Meszaros, mean per QP", "mm/active-set", "mm/ipopt", "");
  line("(c) diesel, warm, per QP", "diesel/active-set", "diesel/ipopt", "(qpOASES 4.7 us)");
  line("(c) crane, warm, per QP", "crane/active-set", "crane/ipopt", "(qpOASES 19 us)");
}

}  // namespace

BENCHMARK_CAPTURE(BodyQpActiveSet, warm, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BodyQpActiveSet, cold, false)->Unit(benchmark::kMicrosecond);
BENCHMARK(BodyQpIpopt)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(MarosMeszarosActiveSet, all, std::string("mm/active-set"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(MarosMeszarosIpopt, all, std::string("mm/ipopt"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SequenceActiveSet, diesel, std::string("diesel"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SequenceIpopt, diesel, std::string("diesel"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SequenceActiveSet, crane, std::string("crane"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SequenceIpopt, crane, std::string("crane"))->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  PrintRatios();
  return 0;
}
