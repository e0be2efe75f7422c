// `stairplan qp`: solve a QP file with a chosen solver, or benchmark solvers over QP files.
//   stairplan qp solve FILE [--solver active-set|banded-ipm|ipopt|nlopt|clp|clp-barrier] [--json] [--time-limit S]
//   stairplan qp bench FILES_OR_DIRS... [--solvers a,b] [--regimes r,s] [--csv OUT] [--summary-csv OUT]
//                      [--plot OUT.svg] [--repeat N] [--max-qps N] [--time-limit S]   (qp_bench.h)
// Exit codes: 0 solved, 3 infeasible or unbounded, 2 bad input (file errors, NaN, bad flags),
// 1 when the solver stops otherwise (limits, numerical trouble).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/cli_common.h"
#include "cli/qp_bench.h"
#include "stairplan/solvers/clp_solver.h"
#include "stairplan/planning/json_version.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"
#include "stairplan/optim/oqp_reader.h"
#include "stairplan/optim/qps_reader.h"
#include "stairplan/optim/solver.h"

namespace stairplan::cli {
namespace {

using optim::SolveResult;
using optim::SolveStatus;

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

int RunSolve(const std::string& file, const std::string& solver_name, bool json, double time_limit) {
  const auto solver = MakeNamedSolver(solver_name, "--solver", time_limit);
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

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

optim::SolveRegime RegimeNamed(const std::string& name) {
  for (optim::SolveRegime r : {optim::SolveRegime::kCold, optim::SolveRegime::kWarmSequence,
                               optim::SolveRegime::kIdenticalResolve}) {
    if (name == optim::ToString(r)) return r;
  }
  throw BadInput("--regimes: unknown regime '" + name + "' (expected cold, warm-sequence or identical-resolve)");
}

int RunQp(const std::vector<std::string>& args) {
  CLI::App app("Solve or benchmark quadratic programs (QPS files, qpOASES sequence folders)", "qp");
  app.require_subcommand(1);
  CLI::App* solve = app.add_subcommand("solve", "Solve one QPS file");
  std::string file, solver = "active-set";
  bool json = false;
  solve->add_option("file", file, "QPS file (Maros-Meszaros format)")->required();
  solve->add_option("--solver", solver, "active-set (default), banded-ipm, ipopt, nlopt, clp or clp-barrier");
  solve->add_flag("--json", json, "Print one JSON object (status, objective, iterations, solve_time_us, max_violation, x)");
  double time_limit = optim::kInf;
  solve->add_option("--time-limit", time_limit, "Wall-clock limit for the solve [s] (default none)");
  CLI::App* bench = app.add_subcommand("bench", "Benchmark solvers over QP files and folders, regime by regime");
  QpBenchOptions options;
  std::string solvers =
      optim::ClpSolver::IsAvailable() ? "active-set,banded-ipm,ipopt,clp" : "active-set,banded-ipm,ipopt";
  std::string regimes = "cold,identical-resolve,warm-sequence";
  bench->add_option("inputs", options.inputs, "QPS files, folders of them, or qpOASES sequence folders")->required();
  bench->add_option("--solvers", solvers, "Comma-separated solvers, the first the base of the ratios (default " + solvers + ")");
  bench->add_option("--regimes", regimes, "Comma-separated: cold, identical-resolve (single problems), warm-sequence "
                                          "(sequences); cold also runs sequences QP by QP (default all)");
  bench->add_option("--csv", options.csv, "Write one CSV row per problem (per QP of a sequence), solver and regime here");
  bench->add_option("--summary-csv", options.summary_csv, "Write one CSV row per set, regime and solver here");
  bench->add_option("--plot", options.plot, "Write an SVG of the fraction solved within a time, one panel per regime");
  bench->add_option("--repeat", options.repeat, "Solves per single problem and regime (default: until 20 ms, at most 1000)");
  bench->add_option("--max-qps", options.max_qps, "QPs taken from each sequence (default all)");
  bench->add_option("--time-limit", options.time_limit_s, "Per solve [s]; a failure counts this long in the means (default 10)");
  if (const int code = Parse(app, args); code >= 0) return code;
  if (solve->parsed()) return Guarded("qp solve", [&] { return RunSolve(file, solver, json, time_limit); });
  return Guarded("qp bench", [&] {
    options.solvers = SplitList(solvers);
    for (const std::string& name : SplitList(regimes)) options.regimes.push_back(RegimeNamed(name));
    return RunQpBench(options);
  });
}

const CommandRegistrar kQpRegistrar({"qp", "solve or benchmark QPs (QPS files, Online QP sequences)", RunQp});

}  // namespace
}  // namespace stairplan::cli
