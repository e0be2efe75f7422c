// The regimes' measuring loops and qpbenchmark's summary.
#include "stairplan/solvers/qp_benchmark.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/solvers/make_solver.h"

namespace stairplan::optim {
namespace {

// Process CPU time [us]: every thread the solver may start counts, other processes do not.
double CpuMicros() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t mid = v.size() / 2;
  return v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}

// Solves once, timed, and records the outcome into `sample`.
void TimedSolve(Solver& solver, const Program& program, SolveResult* result, QpSample* sample) {
  const double cpu0 = CpuMicros();
  const auto wall0 = std::chrono::steady_clock::now();
  solver.Solve(program, result);
  sample->wall_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - wall0).count();
  sample->cpu_us = CpuMicros() - cpu0;
  sample->status = result->status;
  sample->objective = result->objective;
  sample->iterations = result->info.iterations;
  sample->residuals = ComputeQpResiduals(program, *result);
}

// Repeats `solve` (which fills a sample) as the settings say; the first sample's outcome with
// the median times.
template <typename SolveOnce>
QpSample Repeat(const QpMeasureSettings& settings, SolveOnce solve) {
  settings.Validate();
  QpSample first;
  std::vector<double> cpu, wall;
  double total = 0.0;
  while (static_cast<int>(cpu.size()) < settings.max_repeats && (cpu.empty() || total < settings.min_total_us)) {
    QpSample s;
    solve(&s);
    if (cpu.empty()) first = s;
    cpu.push_back(s.cpu_us);
    wall.push_back(s.wall_us);
    total += s.cpu_us;
  }
  first.cpu_us = Median(cpu);
  first.wall_us = Median(wall);
  return first;
}

}  // namespace

bool QpSample::SolvedWithin(double tolerance) const {
  return status == SolveStatus::kSolved && residuals.Within(tolerance);
}

void QpMeasureSettings::Validate() const {
  if (max_repeats < 1) throw std::invalid_argument("QpMeasureSettings::max_repeats must be at least 1");
  if (!(min_total_us >= 0)) throw std::invalid_argument("QpMeasureSettings::min_total_us must be >= 0");
}

void UseBenchmarkAccuracy(Solver* solver) {
  if (auto* ours = dynamic_cast<ActiveSetQpSolver*>(solver)) {
    ours->settings().refinement_steps = ActiveSetQpSettings::kHighAccuracyRefinementSteps;
  }
}

SolverFactory BenchmarkSolverFactory(const std::string& name, double time_limit_s) {
  return [name, time_limit_s] {
    std::unique_ptr<Solver> solver = MakeSolver(name, time_limit_s);
    UseBenchmarkAccuracy(solver.get());
    return solver;
  };
}

QpSample MeasureCold(const SolverFactory& make, const Program& program, const QpMeasureSettings& settings) {
  Program cold = program;
  cold.MutableInitialGuess().setZero();  // no guess
  SolveResult result;
  return Repeat(settings, [&](QpSample* s) {
    const std::unique_ptr<Solver> solver = make();
    TimedSolve(*solver, cold, &result, s);
  });
}

QpSample MeasureIdenticalResolve(const SolverFactory& make, const Program& program, const QpMeasureSettings& settings) {
  Program same = program;
  const std::unique_ptr<Solver> solver = make();
  SolveResult result;
  solver->Solve(same, &result);  // the first solve is cold: not this regime
  return Repeat(settings, [&](QpSample* s) {
    WarmStartFrom(result, solver.get(), &same);
    TimedSolve(*solver, same, &result, s);
  });
}

std::vector<QpSample> MeasureSequence(const SolverFactory& make, SolveRegime regime, Program* program, int count,
                                      const std::function<void(int k, Program* program)>& apply) {
  if (regime == SolveRegime::kIdenticalResolve) {
    throw std::invalid_argument("MeasureSequence: identical re-solve is not a sequence regime");
  }
  const Eigen::VectorXd guess = program->initial_guess();
  std::vector<QpSample> samples;
  SolveResult result;
  std::unique_ptr<Solver> solver;
  for (int k = 0; k < count; ++k) {
    apply(k, program);
    QpSample s;
    if (regime == SolveRegime::kCold) {
      solver = make();
      program->MutableInitialGuess().setZero();
      TimedSolve(*solver, *program, &result, &s);
      samples.push_back(s);
    } else if (k == 0) {
      solver = make();
      solver->Solve(*program, &result);  // problem 0 has no previous solution: cold, not counted
    } else {
      WarmStartFrom(result, solver.get(), program);
      TimedSolve(*solver, *program, &result, &s);
      samples.push_back(s);
    }
  }
  program->MutableInitialGuess() = guess;
  return samples;
}

double ShiftedGeometricMean(const std::vector<double>& values, double shift) {
  if (values.empty()) return 0.0;
  double log_sum = 0.0;
  for (double v : values) log_sum += std::log(v + shift);
  return std::exp(log_sum / static_cast<double>(values.size())) - shift;
}

QpBenchSummary Summarise(const std::vector<QpSample>& samples, double failure_us) {
  QpBenchSummary out;
  std::vector<double> times;
  for (const QpSample& s : samples) {
    ++out.problems;
    const bool mid = s.SolvedWithin(kMidAccuracy);
    out.solved_mid += mid ? 1 : 0;
    out.solved_high += s.SolvedWithin(kHighAccuracy) ? 1 : 0;
    times.push_back(mid ? s.cpu_us : failure_us);
  }
  out.shifted_geomean_us = ShiftedGeometricMean(times, kGeomeanShiftUs);
  return out;
}

std::string DescribeMachine() {
  std::string model = "unknown CPU", line;
  std::ifstream cpuinfo("/proc/cpuinfo");
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  std::string load = "unknown";
  std::ifstream loadavg("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (loadavg >> a >> b >> c) {
    std::ostringstream s;
    s << a << " " << b << " " << c;
    load = s.str();
  }
  std::ostringstream out;
  out << model << ", " << std::thread::hardware_concurrency() << " logical CPUs, load average " << load;
  return out.str();
}

}  // namespace stairplan::optim
