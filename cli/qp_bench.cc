// `stairplan qp bench`: the cases, each solver measured in each regime that applies, the tables,
// the qpbenchmark-style summary with its ratios (within a regime only), the problems our solver
// leaves unsolved at 1e-9, and the CSV files and the plot.
#include "cli/qp_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

#include "cli/cli_common.h"
#include "cli/qp_bench_plot.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/solvers/clp_solver.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"
#include "stairplan/optim/oqp_reader.h"
#include "stairplan/solvers/qp_benchmark.h"
#include "stairplan/optim/qps_reader.h"
#include "stairplan/solvers/make_solver.h"

namespace stairplan::cli {
namespace {

using optim::QpSample;
using optim::SolveRegime;

// A benchmark case: one QPS file, or a qpOASES sequence folder.
struct BenchCase {
  std::string name;
  std::string path;
  bool sequence = false;
};

bool IsQpsFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".sif" || ext == ".qps";
}

// Single problems first, then sequences, each in the order given (folders sorted by name).
std::vector<BenchCase> CollectCases(const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<BenchCase> cases;
  for (const std::string& input : inputs) {
    if (fs::is_directory(input)) {
      if (fs::exists(fs::path(input) / "dims.oqp")) {
        cases.push_back({fs::path(input).lexically_normal().filename().string(), input, true});
        continue;
      }
      std::vector<BenchCase> found;
      for (const auto& entry : fs::directory_iterator(input)) {
        if (entry.is_regular_file() && IsQpsFile(entry.path())) {
          found.push_back({entry.path().filename().string(), entry.path().string(), false});
        } else if (entry.is_directory() && fs::exists(entry.path() / "dims.oqp")) {
          found.push_back({entry.path().filename().string(), entry.path().string(), true});
        }
      }
      std::sort(found.begin(), found.end(), [](const BenchCase& a, const BenchCase& b) { return a.name < b.name; });
      cases.insert(cases.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(input)) {
      cases.push_back({fs::path(input).filename().string(), input, false});
    } else {
      throw BadInput(input + ": no such file or folder");
    }
  }
  if (cases.empty()) throw BadInput("no QP files found (*.SIF, *.qps, or folders with dims.oqp)");
  std::stable_partition(cases.begin(), cases.end(), [](const BenchCase& c) { return !c.sequence; });
  return cases;
}

std::string FormatTime(double us) {
  char text[32];
  if (us < 1e3) std::snprintf(text, sizeof(text), "%.1f us", us);
  else if (us < 1e6) std::snprintf(text, sizeof(text), "%.2f ms", us / 1e3);
  else std::snprintf(text, sizeof(text), "%.2f s", us / 1e6);
  return text;
}

// qpbenchmark's accuracy reached, else why not.
std::string Accuracy(const QpSample& s) {
  if (s.SolvedWithin(optim::kHighAccuracy)) return "1e-9";
  if (s.SolvedWithin(optim::kMidAccuracy)) return "1e-6";
  if (s.status == optim::SolveStatus::kSolved) return "inaccurate";
  return std::string(optim::ToString(s.status));
}

std::string Residuals(const QpSample& s) {
  char text[96];
  std::snprintf(text, sizeof(text), "r_p %.1e r_d %.1e gap %.1e", s.residuals.primal, s.residuals.dual, s.residuals.gap);
  return text;
}

// The samples of one solver in one regime on one case: one for a single problem, one per QP of a
// sequence (a warm sequence's first QP, solved cold, excluded).
struct RunRecord {
  std::string set;      // "QPS files" or the sequence's name: summaries never mix sets
  std::string problem;  // the file's name or the sequence's
  std::string solver;
  SolveRegime regime = SolveRegime::kCold;
  std::vector<QpSample> samples;
};

class Bench {
 public:
  explicit Bench(const QpBenchOptions& options) : o_(options) {
    if (o_.repeat > 0) {
      measure_.max_repeats = o_.repeat;
      measure_.min_total_us = 0.0;
    }
  }

  void Run(const std::vector<BenchCase>& cases);
  void PrintSummary() const;
  void WriteFiles() const;

 private:
  bool Wanted(SolveRegime r) const { return std::find(o_.regimes.begin(), o_.regimes.end(), r) != o_.regimes.end(); }
  optim::SolverFactory Factory(const std::string& name) const {
    return [this, name] {
      std::unique_ptr<optim::Solver> solver = MakeNamedSolver(name, "--solvers", o_.time_limit_s);
      optim::UseBenchmarkAccuracy(solver.get());
      return solver;
    };
  }
  void RunFile(const BenchCase& c);
  void RunSequence(const BenchCase& c);
  // The runs of one set and regime, by solver in --solvers order.
  std::vector<std::pair<std::string, std::vector<QpSample>>> Pooled(const std::string& set, SolveRegime r) const;
  std::vector<std::pair<std::string, SolveRegime>> SetsAndRegimes() const;
  void PrintUnsolved(const std::string& set, SolveRegime regime) const;

  const QpBenchOptions& o_;
  optim::QpMeasureSettings measure_;
  std::vector<RunRecord> runs_;
};

void Bench::RunFile(const BenchCase& c) {
  const optim::QpsProblem qp = optim::ReadQpsFile(c.path);  // std::invalid_argument names the file and line
  std::cout << std::left << std::setw(12) << c.name.substr(0, c.name.find('.'));
  for (const std::string& solver : o_.solvers) {
    std::cout << "| ";
    for (SolveRegime regime : {SolveRegime::kCold, SolveRegime::kIdenticalResolve}) {
      if (!Wanted(regime)) continue;
      const QpSample s = regime == SolveRegime::kCold ? optim::MeasureCold(Factory(solver), qp.program, measure_)
                                                      : optim::MeasureIdenticalResolve(Factory(solver), qp.program, measure_);
      std::ostringstream cell;
      if (regime == SolveRegime::kCold) {
        cell << FormatTime(s.cpu_us) << " " << s.iterations << "it " << Accuracy(s);
        std::cout << std::setw(30) << cell.str();
      } else {
        cell << FormatTime(s.cpu_us) << (s.SolvedWithin(optim::kMidAccuracy) ? "" : " " + Accuracy(s));
        std::cout << std::setw(13) << cell.str();
      }
      std::cout << std::flush;
      runs_.push_back({"QPS files", c.name, solver, regime, {s}});
    }
  }
  std::cout << "\n";
}

void Bench::RunSequence(const BenchCase& c) {
  const optim::OqpSequence sequence = optim::ReadOqpSequence(c.path);  // errors name the file and line
  const int count = o_.max_qps > 0 ? std::min(o_.max_qps, sequence.num_qps) : sequence.num_qps;
  for (const std::string& solver : o_.solvers) {
    for (SolveRegime regime : {SolveRegime::kWarmSequence, SolveRegime::kCold}) {
      if (!Wanted(regime)) continue;
      optim::Program program = sequence.MakeProgram();
      std::vector<QpSample> samples = optim::MeasureSequence(
          Factory(solver), regime, &program, count, [&](int k, optim::Program* p) { sequence.Apply(k, p); });
      double total = 0, worst = 0, iterations = 0;
      int mid = 0, high = 0;
      for (const QpSample& s : samples) {
        total += s.cpu_us;
        worst = std::max(worst, s.cpu_us);
        iterations += s.iterations;
        mid += s.SolvedWithin(optim::kMidAccuracy) ? 1 : 0;
        high += s.SolvedWithin(optim::kHighAccuracy) ? 1 : 0;
      }
      const double n = std::max<double>(1.0, static_cast<double>(samples.size()));
      std::cout << std::left << std::setw(10) << c.name << std::setw(13) << solver << std::setw(15)
                << optim::ToString(regime) << std::right << std::setw(5) << samples.size() << std::setw(12)
                << FormatTime(total / n) << std::setw(12) << FormatTime(worst) << std::setw(9) << std::fixed
                << std::setprecision(1) << iterations / n << std::defaultfloat << std::setw(7) << mid << std::setw(7)
                << high << "\n"
                << std::flush;
      runs_.push_back({c.name, c.name, solver, regime, std::move(samples)});
    }
  }
}

void Bench::Run(const std::vector<BenchCase>& cases) {
  const bool files = std::any_of(cases.begin(), cases.end(), [](const BenchCase& c) { return !c.sequence; });
  if (files && (Wanted(SolveRegime::kCold) || Wanted(SolveRegime::kIdenticalResolve))) {
    std::cout << "\nsingle problems: cold = a fresh solver object per solve, no guess; re-solve = the identical problem "
                 "again\non the same solver from its own last solution (its own regime: never compare it with cold). "
                 "Median CPU time\nof the repeats; iterations; qpbenchmark accuracy reached (1e-9, 1e-6) or the status.\n";
    std::cout << std::left << std::setw(12) << "problem";
    for (const std::string& solver : o_.solvers) {
      std::cout << "| ";
      if (Wanted(SolveRegime::kCold)) std::cout << std::setw(30) << solver + " cold";
      if (Wanted(SolveRegime::kIdenticalResolve)) std::cout << std::setw(13) << "re-solve";
    }
    std::cout << "\n";
    for (const BenchCase& c : cases) {
      if (!c.sequence) RunFile(c);
    }
  }
  const bool sequences = std::any_of(cases.begin(), cases.end(), [](const BenchCase& c) { return c.sequence; });
  if (sequences && (Wanted(SolveRegime::kWarmSequence) || Wanted(SolveRegime::kCold))) {
    std::cout << "\nsequences: warm-sequence = QP k from QP k-1's solution on the same solver (Ipopt with its "
                 "multipliers,\nwarm_start_init_point), QP 0 solved cold and not counted; cold = a fresh solver per QP. "
                 "CPU time per QP;\nsolved = qpbenchmark's success at 1e-6 and 1e-9.\n";
    std::cout << std::left << std::setw(10) << "sequence" << std::setw(13) << "solver" << std::setw(15) << "regime"
              << std::right << std::setw(5) << "QPs" << std::setw(12) << "mean/QP" << std::setw(12) << "max/QP"
              << std::setw(9) << "it/QP" << std::setw(7) << "1e-6" << std::setw(7) << "1e-9" << "\n";
    for (const BenchCase& c : cases) {
      if (c.sequence) RunSequence(c);
    }
  }
}

std::vector<std::pair<std::string, SolveRegime>> Bench::SetsAndRegimes() const {
  std::vector<std::pair<std::string, SolveRegime>> out;
  for (const RunRecord& r : runs_) {
    if (std::find(out.begin(), out.end(), std::make_pair(r.set, r.regime)) == out.end()) out.emplace_back(r.set, r.regime);
  }
  return out;
}

std::vector<std::pair<std::string, std::vector<QpSample>>> Bench::Pooled(const std::string& set, SolveRegime regime) const {
  std::vector<std::pair<std::string, std::vector<QpSample>>> out;
  for (const std::string& solver : o_.solvers) {
    std::vector<QpSample> samples;
    for (const RunRecord& r : runs_) {
      if (r.set == set && r.regime == regime && r.solver == solver) samples.insert(samples.end(), r.samples.begin(), r.samples.end());
    }
    out.emplace_back(solver, std::move(samples));
  }
  return out;
}

// The problems the base solver (the first) leaves unsolved at 1e-9, with its residuals and the
// references that reach 1e-9 there.
void Bench::PrintUnsolved(const std::string& set, SolveRegime regime) const {
  std::vector<std::tuple<std::string, const QpSample*, std::string>> misses;
  const std::string& base = o_.solvers.front();
  for (const RunRecord& r : runs_) {
    if (r.set != set || r.regime != regime || r.solver != base) continue;
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
      if (r.samples[k].SolvedWithin(optim::kHighAccuracy)) continue;
      std::string references;
      for (const RunRecord& other : runs_) {
        if (other.problem == r.problem && other.regime == regime && other.solver != base &&
            k < other.samples.size() && other.samples[k].SolvedWithin(optim::kHighAccuracy)) {
          references += (references.empty() ? "" : ", ") + other.solver;
        }
      }
      const std::string name = r.samples.size() > 1 ? r.problem + " QP " + std::to_string(k + 1) : r.problem;
      misses.emplace_back(name, &r.samples[k], references.empty() ? "none" : references);
    }
  }
  if (misses.empty()) return;
  std::cout << "  not solved at 1e-9 by " << base << " (" << set << ", " << optim::ToString(regime) << "): " << misses.size()
            << "\n";
  constexpr std::size_t kShown = 20;
  for (std::size_t i = 0; i < misses.size() && i < kShown; ++i) {
    const auto& [name, s, references] = misses[i];
    std::cout << "    " << std::left << std::setw(16) << name << std::setw(16) << Accuracy(*s) << Residuals(*s)
              << "   1e-9 by: " << references << "\n";
  }
  if (misses.size() > kShown) std::cout << "    ... and " << misses.size() - kShown << " more (see --csv)\n";
}

void Bench::PrintSummary() const {
  const double failure_us = 1e6 * o_.time_limit_s;
  std::cout << std::defaultfloat << std::setprecision(6);
  std::cout << "\nsummary, qpbenchmark style: solved = status solved with primal residual, dual residual and duality gap"
               "\nall below the tolerance; time = shifted geometric mean of the CPU times, shift "
            << optim::kGeomeanShiftUs << " us, a problem not\nsolved at 1e-6 counted at the time limit ("
            << o_.time_limit_s << " s). Ratios only within a regime, against " << o_.solvers.front() << ".\n";
  std::cout << std::left << std::setw(12) << "set" << std::setw(19) << "regime" << std::setw(13) << "solver"
            << std::right << std::setw(9) << "problems" << std::setw(11) << "1e-6" << std::setw(11) << "1e-9"
            << std::setw(14) << "time (shm)" << "\n";
  for (const auto& [set, regime] : SetsAndRegimes()) {
    const auto pooled = Pooled(set, regime);
    for (const auto& [solver, samples] : pooled) {
      if (samples.empty()) continue;
      const optim::QpBenchSummary s = optim::Summarise(samples, failure_us);
      std::cout << std::left << std::setw(12) << set << std::setw(19) << optim::ToString(regime) << std::setw(13) << solver
                << std::right << std::setw(9) << s.problems << std::setw(11) << s.solved_mid << std::setw(11)
                << s.solved_high << std::setw(14) << FormatTime(s.shifted_geomean_us) << "\n";
    }
  }
  std::cout << "\nratios of the shifted geometric means (other / " << o_.solvers.front()
            << "; above 1: slower than it), and over\nthe problems both solve at 1e-6 (no failure time):\n";
  for (const auto& [set, regime] : SetsAndRegimes()) {
    const auto pooled = Pooled(set, regime);
    const std::vector<QpSample>& base = pooled.front().second;
    if (base.empty()) continue;
    const double base_shm = optim::Summarise(base, failure_us).shifted_geomean_us;
    for (std::size_t i = 1; i < pooled.size(); ++i) {
      const std::vector<QpSample>& other = pooled[i].second;
      if (other.size() != base.size()) continue;
      std::vector<double> a, b;
      for (std::size_t k = 0; k < base.size(); ++k) {
        if (base[k].SolvedWithin(optim::kMidAccuracy) && other[k].SolvedWithin(optim::kMidAccuracy)) {
          a.push_back(base[k].cpu_us);
          b.push_back(other[k].cpu_us);
        }
      }
      const double both = a.empty() ? NAN
                                    : optim::ShiftedGeometricMean(b, optim::kGeomeanShiftUs) /
                                          optim::ShiftedGeometricMean(a, optim::kGeomeanShiftUs);
      std::cout << "  " << set << ", " << optim::ToString(regime) << ": " << pooled[i].first << " / "
                << o_.solvers.front() << " = " << std::setprecision(3)
                << optim::Summarise(other, failure_us).shifted_geomean_us / base_shm << "  (both solved, " << a.size()
                << " problems: " << both << ")\n";
    }
  }
  std::cout << "\n";
  for (const auto& [set, regime] : SetsAndRegimes()) PrintUnsolved(set, regime);
}

void Bench::WriteFiles() const {
  const double failure_us = 1e6 * o_.time_limit_s;
  if (!o_.csv.empty()) {
    std::ostringstream rows;
    rows << "problem,qp,solver,regime,status,objective,iterations,cpu_us,wall_us,primal_residual,dual_residual,"
            "duality_gap,solved_1e-6,solved_1e-9\n"
         << std::setprecision(10);
    for (const RunRecord& r : runs_) {
      for (std::size_t k = 0; k < r.samples.size(); ++k) {
        const QpSample& s = r.samples[k];
        // A warm sequence's samples start at QP 1 (QP 0 is its cold start).
        const std::size_t qp = r.regime == SolveRegime::kWarmSequence ? k + 1 : k;
        rows << r.problem << "," << qp << "," << r.solver << "," << optim::ToString(r.regime) << ","
             << optim::ToString(s.status) << "," << s.objective << "," << s.iterations << "," << s.cpu_us << ","
             << s.wall_us << "," << s.residuals.primal << "," << s.residuals.dual << "," << s.residuals.gap << ","
             << s.SolvedWithin(optim::kMidAccuracy) << "," << s.SolvedWithin(optim::kHighAccuracy) << "\n";
      }
    }
    WriteFileAtomically(o_.csv, rows.str());
  }
  if (!o_.summary_csv.empty()) {
    std::ostringstream rows;
    rows << "set,regime,solver,problems,solved_1e-6,solved_1e-9,shifted_geomean_cpu_us,shift_us,failure_us\n";
    for (const auto& [set, regime] : SetsAndRegimes()) {
      for (const auto& [solver, samples] : Pooled(set, regime)) {
        if (samples.empty()) continue;
        const optim::QpBenchSummary s = optim::Summarise(samples, failure_us);
        rows << set << "," << optim::ToString(regime) << "," << solver << "," << s.problems << "," << s.solved_mid << ","
             << s.solved_high << "," << std::setprecision(6) << s.shifted_geomean_us << "," << optim::kGeomeanShiftUs
             << "," << failure_us << "\n";
      }
    }
    WriteFileAtomically(o_.summary_csv, rows.str());
  }
  if (!o_.plot.empty()) {
    std::vector<QpBenchPanel> panels;
    for (const auto& [set, regime] : SetsAndRegimes()) {
      QpBenchPanel panel;
      for (const auto& [solver, samples] : Pooled(set, regime)) {
        if (samples.empty()) continue;
        QpBenchCurve curve{solver, {}};
        for (const QpSample& s : samples) {
          if (s.SolvedWithin(optim::kMidAccuracy)) curve.solved_us.push_back(s.cpu_us);
        }
        panel.problems = static_cast<int>(samples.size());
        panel.curves.push_back(std::move(curve));
      }
      panel.title = set + ", " + std::string(optim::ToString(regime)) + ", " + std::to_string(panel.problems) +
                    (panel.problems == 1 ? " problem" : " problems");
      panels.push_back(std::move(panel));
    }
    WriteFileAtomically(o_.plot, QpBenchPlotSvg(panels, "fraction solved at 1e-6 (qpbenchmark residuals) within a CPU "
                                                        "time per solve; " + optim::DescribeMachine()));
  }
}

}  // namespace

std::unique_ptr<optim::Solver> MakeNamedSolver(const std::string& name, const std::string& flag, double time_limit_s) {
  if (!(time_limit_s > 0)) throw BadInput("--time-limit: must be a positive number of seconds");
  try {
    return optim::MakeSolver(name, time_limit_s);
  } catch (const std::invalid_argument& e) {
    throw BadInput(flag + ": " + e.what());
  }
}

int RunQpBench(const QpBenchOptions& options) {
  if (options.repeat < 0) throw BadInput("--repeat: must be >= 0");
  if (options.max_qps < 0) throw BadInput("--max-qps: must be >= 0");
  if (options.solvers.empty()) throw BadInput("--solvers: no solver named");
  if (options.regimes.empty()) throw BadInput("--regimes: no regime named");
  for (const std::string& name : options.solvers) MakeNamedSolver(name, "--solvers", options.time_limit_s);
  const std::vector<BenchCase> cases = CollectCases(options.inputs);
  std::cout << "stairplan qp bench: " << cases.size() << " cases; machine: " << optim::DescribeMachine() << "\n";
  Bench bench(options);
  bench.Run(cases);
  bench.PrintSummary();
  bench.WriteFiles();
  return kExitOk;
}

}  // namespace stairplan::cli
