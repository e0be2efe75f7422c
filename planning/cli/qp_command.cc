// `stairplan qp`: solve a QP file with a chosen solver, or benchmark solvers over QP files.
//   stairplan qp solve FILE [--solver active-set|ipopt|nlopt] [--json] [--time-limit S]
//   stairplan qp bench FILES_OR_DIRS... [--solvers a,b] [--csv OUT] [--repeat N]
// Exit codes: 0 solved, 3 infeasible or unbounded, 2 bad input (file errors, NaN, bad flags),
// 1 when the solver stops otherwise (limits, numerical trouble).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "planning/cli/cli_common.h"
#include "planning/json_version.h"
#include "planning/optim/active_set_qp_solver.h"
#include "planning/optim/ipopt_solver.h"
#include "planning/optim/nlopt_solver.h"
#include "planning/optim/oqp_reader.h"
#include "planning/optim/qps_reader.h"
#include "planning/optim/solver.h"

namespace stairplan::cli {
namespace {

using optim::SolveResult;
using optim::SolveStatus;

std::unique_ptr<optim::Solver> SolverNamed(const std::string& name, const std::string& flag) {
  try {
    return optim::MakeSolver(name);
  } catch (const std::invalid_argument& e) {
    throw BadInput(flag + ": " + e.what());
  }
}

int ExitCodeFor(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSolved: return kExitOk;
    case SolveStatus::kInfeasible:
    case SolveStatus::kUnbounded: return kExitInfeasible;
    case SolveStatus::kInvalidInput: return kExitBadInput;
    default: return 1;
  }
}

optim::QpsProblem LoadQps(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw BadInput(path + ": no such file");
  return optim::ReadQpsFile(path);  // std::invalid_argument names the file and line
}

void SetTimeLimit(optim::Solver& solver, double seconds) {
  if (!(seconds > 0)) throw BadInput("--time-limit: must be a positive number of seconds");
  if (auto* s = dynamic_cast<optim::ActiveSetQpSolver*>(&solver)) s->settings().time_limit_s = seconds;
  if (auto* s = dynamic_cast<optim::IpoptSolver*>(&solver)) s->settings().time_limit_s = seconds;
  if (auto* s = dynamic_cast<optim::NloptSolver*>(&solver)) s->settings().time_limit_s = seconds;
}

int RunSolve(const std::string& file, const std::string& solver_name, bool json, double time_limit) {
  const auto solver = SolverNamed(solver_name, "--solver");
  SetTimeLimit(*solver, time_limit);
  const optim::QpsProblem qp = LoadQps(file);
  const SolveResult r = solver->Solve(qp.program);
  const double violation = r.x.allFinite() ? qp.program.MaxViolation(r.x) : NAN;
  if (json) {
    nlohmann::json out;
    out["problem"] = qp.name;
    out["solver"] = std::string(solver->name());
    out["status"] = std::string(optim::ToString(r.status));
    out["objective"] = r.objective;
    out["iterations"] = r.info.iterations;
    out["solve_time_us"] = r.info.solve_time_us;
    out["max_violation"] = violation;
    out["x"] = std::vector<double>(r.x.data(), r.x.data() + r.x.size());
    std::cout << StampVersion(out).dump(2) << "\n";
  } else {
    std::cout << "stairplan qp solve: " << file << " (" << qp.program.num_variables() << " variables, "
              << qp.program.num_rows() << " rows)\n"
              << "  solver:        " << solver->name() << "\n"
              << "  status:        " << optim::ToString(r.status) << "\n"
              << "  objective:     " << std::setprecision(12) << r.objective << "\n"
              << "  iterations:    " << r.info.iterations << "\n"
              << "  time:          " << std::setprecision(4) << r.info.solve_time_us << " us\n"
              << "  max violation: " << std::setprecision(3) << violation << "\n";
  }
  if (r.status == SolveStatus::kInvalidInput) {
    std::cerr << "stairplan qp solve: " << file << ": invalid input (NaN in the data, or a problem "
              << solver->name() << " cannot handle)\n";
  }
  return ExitCodeFor(r.status);
}

bool IsQpsFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".sif" || ext == ".qps";
}

// A benchmark case: one QPS file, or a qpOASES sequence folder solved warm QP after QP.
struct BenchCase {
  std::string name;
  std::string path;
  bool sequence = false;
};

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
  return cases;
}

struct Measurement {
  SolveStatus status = SolveStatus::kInvalidInput;
  double objective = 0.0;
  int iterations = 0;
  double time_us = 0.0;  // per solve (per QP for sequences)
  bool inaccurate = false;  // a sequence QP solved but farther than 1e-6 from its reference
  bool success() const { return status == SolveStatus::kSolved && !inaccurate; }
  std::string label() const { return inaccurate ? "inaccurate" : std::string(optim::ToString(status)); }
};

// Repeats until `repeat` runs, or (repeat = 0) at least 20 ms in total; reports the mean.
Measurement MeasureFile(optim::Solver& solver, const optim::Program& program, int repeat) {
  Measurement m;
  SolveResult r;
  double total = 0.0;
  int runs = 0;
  while (repeat > 0 ? runs < repeat : (runs < 1000 && (runs < 1 || total < 2e4))) {
    const auto start = std::chrono::steady_clock::now();
    solver.Solve(program, &r);
    total += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    ++runs;
  }
  m.status = r.status;
  m.objective = r.objective;
  m.iterations = r.info.iterations;
  m.time_us = total / runs;
  return m;
}

Measurement MeasureSequence(optim::Solver& solver, const optim::OqpSequence& s, int repeat) {
  Measurement m;
  m.status = SolveStatus::kSolved;
  optim::Program program = s.MakeProgram();
  SolveResult r;
  double total = 0.0;
  const int runs = std::max(1, repeat);
  for (int run = 0; run < runs; ++run) {
    for (int k = 0; k < s.num_qps; ++k) {
      s.Apply(k, &program);
      const auto start = std::chrono::steady_clock::now();
      solver.Solve(program, &r);
      total += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      if (run == 0) {
        m.iterations += r.info.iterations;
        const Eigen::VectorXd reference = s.x_opt.row(k).transpose();
        const double error = (r.x - reference).lpNorm<Eigen::Infinity>() / std::max(1.0, reference.lpNorm<Eigen::Infinity>());
        if (r.status != SolveStatus::kSolved) m.status = r.status;
        if (error > 1e-6) m.inaccurate = true;
      }
    }
  }
  m.objective = r.objective;
  m.time_us = total / (static_cast<double>(runs) * s.num_qps);
  return m;
}

// Shifted geometric mean (shift 10 us), the usual way to average solve times across problems.
double ShiftedGeometricMean(const std::vector<double>& times) {
  constexpr double kShift = 10.0;
  double log_sum = 0.0;
  for (double t : times) log_sum += std::log(t + kShift);
  return std::exp(log_sum / static_cast<double>(times.size())) - kShift;
}

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

int RunBench(const std::vector<std::string>& inputs, const std::string& solvers_flag, const std::string& csv, int repeat) {
  if (repeat < 0) throw BadInput("--repeat: must be >= 0");
  std::vector<std::unique_ptr<optim::Solver>> solvers;
  for (const std::string& name : SplitList(solvers_flag)) solvers.push_back(SolverNamed(name, "--solvers"));
  if (solvers.empty()) throw BadInput("--solvers: no solver named");
  const std::vector<BenchCase> cases = CollectCases(inputs);
  std::ostringstream rows;
  rows << "problem,solver,status,objective,iterations,time_us\n";
  std::map<std::string, std::vector<double>> times;
  std::map<std::string, int> successes;
  std::cout << std::left << std::setw(14) << "problem";
  for (const auto& s : solvers) std::cout << std::setw(34) << s->name();
  std::cout << "\n";
  for (const BenchCase& c : cases) {
    std::cout << std::setw(14) << c.name;
    optim::OqpSequence sequence;
    optim::QpsProblem qp;
    if (c.sequence) sequence = optim::ReadOqpSequence(c.path);
    else qp = LoadQps(c.path);
    for (auto& solver : solvers) {
      const Measurement m = c.sequence ? MeasureSequence(*solver, sequence, repeat) : MeasureFile(*solver, qp.program, repeat);
      const std::string name(solver->name());
      times[name].push_back(m.time_us);
      successes[name] += m.success() ? 1 : 0;
      std::ostringstream cell;
      cell << m.label() << " " << std::setprecision(4) << m.time_us << " us";
      std::cout << std::setw(34) << cell.str();
      rows << c.name << "," << name << "," << m.label() << "," << std::setprecision(17) << m.objective
           << "," << m.iterations << "," << m.time_us << "\n";
    }
    std::cout << "\n";
  }
  std::cout << "\nsolver        solved   shifted geomean time (sequences: solved within 1e-6 of the reference)\n";
  for (const auto& s : solvers) {
    const std::string name(s->name());
    std::ostringstream solved;
    solved << successes[name] << "/" << cases.size();
    std::cout << std::setw(14) << name << std::setw(9) << solved.str() << std::setprecision(4)
              << ShiftedGeometricMean(times[name]) << " us\n";
  }
  for (std::size_t a = 0; a < solvers.size(); ++a) {
    for (std::size_t b = a + 1; b < solvers.size(); ++b) {
      const std::string na(solvers[a]->name()), nb(solvers[b]->name());
      std::cout << "ratio " << nb << " / " << na << ": " << std::setprecision(3)
                << ShiftedGeometricMean(times[nb]) / ShiftedGeometricMean(times[na]) << "\n";
    }
  }
  if (!csv.empty()) WriteFileAtomically(csv, rows.str());
  return kExitOk;
}

int RunQp(const std::vector<std::string>& args) {
  CLI::App app("Solve or benchmark quadratic programs (QPS files, qpOASES sequence folders)", "qp");
  app.require_subcommand(1);
  CLI::App* solve = app.add_subcommand("solve", "Solve one QPS file");
  std::string file, solver = "active-set";
  bool json = false;
  solve->add_option("file", file, "QPS file (Maros-Meszaros format)")->required();
  solve->add_option("--solver", solver, "active-set (default), ipopt or nlopt");
  solve->add_flag("--json", json, "Print one JSON object (status, objective, iterations, solve_time_us, max_violation, x)");
  double time_limit = optim::kInf;
  solve->add_option("--time-limit", time_limit, "Wall-clock limit for the solve [s] (default none)");
  CLI::App* bench = app.add_subcommand("bench", "Benchmark solvers over QP files and folders");
  std::vector<std::string> inputs;
  std::string solvers = "active-set,ipopt", csv;
  int repeat = 0;
  bench->add_option("inputs", inputs, "QPS files, folders of them, or qpOASES sequence folders")->required();
  bench->add_option("--solvers", solvers, "Comma-separated solvers (default active-set,ipopt)");
  bench->add_option("--csv", csv, "Write one CSV row per problem and solver here");
  bench->add_option("--repeat", repeat, "Solves per problem (default: repeat until 20 ms, at most 1000)");
  if (const int code = Parse(app, args); code >= 0) return code;
  if (solve->parsed()) return Guarded("qp solve", [&] { return RunSolve(file, solver, json, time_limit); });
  return Guarded("qp bench", [&] { return RunBench(inputs, solvers, csv, repeat); });
}

const CommandRegistrar kRegistrar({"qp", "solve or benchmark QPs (QPS files, Online QP sequences)", RunQp});

}  // namespace
}  // namespace stairplan::cli
