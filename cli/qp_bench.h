// `stairplan qp bench`: QP solvers over QPS files and Online QP sequences, regime by regime
// (cold and identical re-solve for single problems; warm sequence and cold for sequences), with
// qpbenchmark's success rates and shifted geometric means, ratios only within a regime.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stairplan/solvers/solve_regime.h"
#include "stairplan/optim/solver.h"

namespace stairplan::cli {

/// What `qp bench` was asked for.
struct QpBenchOptions {
  std::vector<std::string> inputs;   ///< QPS files, folders of them, sequence folders
  std::vector<std::string> solvers;  ///< the first is the base of the ratios
  /// The regimes to run (those that apply to a case: single problems cold and identical
  /// re-solve, sequences warm sequence and cold).
  std::vector<optim::SolveRegime> regimes;
  int repeat = 0;             ///< solves per single problem and regime; 0: until 20 ms, at most 1000
  int max_qps = 0;            ///< QPs taken from each sequence; 0: all
  double time_limit_s = 10;   ///< per solve; also the time a failure counts in the means
  std::string csv, summary_csv, plot;
};

/// A solver by name with a time limit [s]; BadInput naming `flag` for an unknown name.
std::unique_ptr<optim::Solver> MakeNamedSolver(const std::string& name, const std::string& flag, double time_limit_s);

/// Runs the benchmark, prints its tables, writes the files asked for; returns the exit code.
int RunQpBench(const QpBenchOptions& options);

}  // namespace stairplan::cli
