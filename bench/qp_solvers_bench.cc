// QP solvers regime by regime (stairplan/solvers/solve_regime.h): our active-set solver, our banded
// interior point (warm: the last active set tried first by one equality-constrained solve, the
// interior point from its own start when that fails), Ipopt and CLP on (a) the
// body-planner-shaped QP (40 knots, 3 variables each, banded rows) along 200 cycles
// of its per-cycle update, cold (a fresh solver per cycle) and warm sequence (each cycle from the
// last one's solution, Ipopt with its multipliers); (b) the Maros-Meszaros set, cold; (c) the
// Online QP sequences diesel and crane, warm sequence. Times are process CPU time per solve;
// ratios are printed only between solvers in the same regime on the same set.
//
//   ./qp_solvers_bench                       (STAIRPLAN_BENCH_SMOKE=1: a few QPs each, for ctest)
//
// Published references for (c), hot-started, hardware not stated: qpOASES 4.7 us (diesel) and
// 19 us (crane) per QP.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "stairplan/optim/body_qp_example.h"
#include "stairplan/solvers/clp_solver.h"
#include "stairplan/optim/oqp_reader.h"
#include "stairplan/solvers/qp_benchmark.h"
#include "stairplan/optim/qps_reader.h"
#include "stairplan/solvers/make_solver.h"

using namespace stairplan::optim;

namespace {

bool Smoke() { return std::getenv("STAIRPLAN_BENCH_SMOKE") != nullptr; }

std::vector<std::string> Solvers() {
  std::vector<std::string> names = {"active-set", "banded-ipm", "ipopt"};
  if (ClpSolver::IsAvailable()) names.push_back("clp");
  return names;
}

// Every solve has `qp bench`'s default limit (a shorter one in the smoke run): CLP's primal simplex
// can cycle on the body QP.
SolverFactory Factory(const std::string& name) { return BenchmarkSolverFactory(name, Smoke() ? 1.0 : 10.0); }

std::string SharedDir() { return STAIRPLAN_SHARED_DIR; }

// Per (set, regime): per solver, the mean and max CPU time per QP and the iterations, for the table.
struct Row {
  double mean_us = 0, max_us = 0, iterations = 0, shm_us = 0;
  int qps = 0, solved = 0;
};
std::map<std::string, std::map<std::string, Row>>& Table() {
  static std::map<std::string, std::map<std::string, Row>> table;
  return table;
}

void Record(benchmark::State& state, const std::string& group, const std::string& solver,
            const std::vector<QpSample>& samples) {
  Row row;
  for (const QpSample& s : samples) {
    row.mean_us += s.cpu_us;
    row.max_us = std::max(row.max_us, s.cpu_us);
    row.iterations += s.iterations;
    row.solved += s.SolvedWithin(kMidAccuracy) ? 1 : 0;
  }
  row.qps = static_cast<int>(samples.size());
  const double n = std::max(1.0, static_cast<double>(samples.size()));
  row.mean_us /= n;
  row.iterations /= n;
  row.shm_us = Summarise(samples, 1e7).shifted_geomean_us;
  Table()[group][solver] = row;
  state.counters["cpu_us_per_qp"] = row.mean_us;
  state.counters["max_cpu_us"] = row.max_us;
  state.counters["it_per_qp"] = row.iterations;
  state.counters["solved_1e-6"] = row.solved;
  state.counters["qps"] = row.qps;
}

// (a) The per-cycle problem: bounds and linear terms change every cycle.
void BodyQp(benchmark::State& state, const std::string& solver, SolveRegime regime) {
  const int cycles = Smoke() ? 4 : 200;
  std::vector<QpSample> samples;
  for (auto _ : state) {
    BodyQpExample e = MakeBodyQpExample(40);
    samples = MeasureSequence(Factory(solver), regime, &e.program, cycles,
                              [&e](int k, Program*) { UpdateBodyQpExample(k, &e); });
  }
  Record(state, "(a) body QP 40 knots, " + std::string(ToString(regime)), solver, samples);
}

// (b) The Maros-Meszaros set, each problem cold (fresh solver, no guess), median of 3.
void MarosMeszaros(benchmark::State& state, const std::string& solver) {
  const std::string dir = SharedDir() + "/data/qp/maros_meszaros";
  if (!std::filesystem::is_directory(dir)) return state.SkipWithError("../shared/data/qp/maros_meszaros not found");
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".SIF") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  if (Smoke()) files.resize(std::min<std::size_t>(files.size(), 3));
  std::vector<QpSample> samples;
  for (auto _ : state) {
    samples.clear();
    for (const std::string& f : files) samples.push_back(MeasureCold(Factory(solver), ReadQpsFile(f).program, {3, 0.0}));
  }
  Record(state, "(b) Maros-Meszaros, cold", solver, samples);
}

// (c) Online QP sequences, QP k warm-started from QP k-1. Ipopt takes the first 100 QPs.
void OnlineSequence(benchmark::State& state, const std::string& name, const std::string& solver) {
  const std::string dir = SharedDir() + "/data/qp/online_qp/" + name;
  if (!std::filesystem::is_directory(dir)) return state.SkipWithError("../shared/data/qp/online_qp not found");
  const OqpSequence s = ReadOqpSequence(dir);
  const int count = Smoke() ? 4 : (solver == "ipopt" ? std::min(100, s.num_qps) : s.num_qps);
  std::vector<QpSample> samples;
  for (auto _ : state) {
    Program p = s.MakeProgram();
    samples = MeasureSequence(Factory(solver), SolveRegime::kWarmSequence, &p, count,
                              [&s](int k, Program* program) { s.Apply(k, program); });
  }
  Record(state, "(c) " + name + ", warm-sequence", solver, samples);
}

void PrintTable() {
  std::printf("\nCPU time per QP by set and regime (ratios only within a row group, against active-set);\n"
              "machine: %s\n", DescribeMachine().c_str());
  for (const auto& [group, rows] : Table()) {
    std::printf("%s\n", group.c_str());
    const auto base = rows.find("active-set");
    for (const auto& [solver, r] : rows) {
      std::printf("  %-11s mean %10.1f us  max %10.1f us  %7.1f it/QP  solved@1e-6 %4d/%-4d  shm %10.1f us", solver.c_str(),
                  r.mean_us, r.max_us, r.iterations, r.solved, r.qps, r.shm_us);
      if (base != rows.end() && solver != "active-set") std::printf("  shm ratio %.3g", r.shm_us / base->second.shm_us);
      std::printf("\n");
    }
  }
}

void RegisterAll() {
  for (const std::string& solver : Solvers()) {
    for (const SolveRegime regime : {SolveRegime::kCold, SolveRegime::kWarmSequence}) {
      benchmark::RegisterBenchmark(("BodyQp/" + std::string(ToString(regime)) + "/" + solver).c_str(), BodyQp, solver,
                                   regime)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark(("MarosMeszaros/cold/" + solver).c_str(), MarosMeszaros, solver)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
    for (const std::string name : {"diesel", "crane"}) {
      benchmark::RegisterBenchmark(("Online/" + name + "/warm-sequence/" + solver).c_str(), OnlineSequence, name, solver)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  RegisterAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  PrintTable();
  return 0;
}
