// Measuring QP solvers regime by regime (solve_regime.h), the same way for `stairplan qp bench`
// and the bench/ programs, and summarising them as qpbenchmark does (success at a tolerance on
// its residuals, shifted geometric mean of the times).
//
//   const SolverFactory make = [] { return MakeSolver("clp"); };
//   QpSample cold = MeasureCold(make, program, {});              // fresh solvers, median time
//   QpSample again = MeasureIdenticalResolve(make, program, {});  // one solver, same problem
//   std::vector<QpSample> warm = MeasureSequence(make, SolveRegime::kWarmSequence, &program, count,
//                                                [&](int k, Program* p) { sequence.Apply(k, p); });
//
// Times are CPU time of this process (the machine running a benchmark is often shared: CPU time
// leaves out what other processes took) beside the wall-clock time; only the solve is timed,
// not building the solver object or changing the data. The library never prints: callers do.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "stairplan/optim/qp_residuals.h"
#include "stairplan/solvers/solve_regime.h"
#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// Makes a fresh solver (a cold start is a new object).
using SolverFactory = std::function<std::unique_ptr<Solver>()>;

///@{
/// qpbenchmark's accuracies: mid (1e-6) and high (1e-9).
constexpr double kMidAccuracy = 1e-6;
constexpr double kHighAccuracy = 1e-9;
///@}

/// One measured solve: its outcome, qpbenchmark's residuals and its time.
struct QpSample {
  SolveStatus status = SolveStatus::kInvalidInput;  ///< how the solve ended
  double objective = 0.0;  ///< the objective at the solution
  int iterations = 0;  ///< the solver's iterations
  QpResiduals residuals;  ///< qpbenchmark's residuals of the solution
  double cpu_us = 0.0;   ///< process CPU time of the solve (median over repeats where repeated)
  double wall_us = 0.0;  ///< wall-clock time of the same solve(s)
  /// qpbenchmark's success at `tolerance`: solved, and all three residuals below it.
  bool SolvedWithin(double tolerance) const;
};

/// How long single problems are repeated (cold and identical re-solve).
struct QpMeasureSettings {
  /// Repeat until this many solves ...
  int max_repeats = 1000;
  /// ... or until the solves took this much CPU time [us] in total (at least one solve).
  double min_total_us = 2e4;
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// The accuracy options a benchmark runs `solver` with: ours refines its final active set
/// (ActiveSetQpSettings::kHighAccuracyRefinementSteps) to meet qpbenchmark's 1e-9 absolute
/// residuals; the references keep their defaults. Its cost is in the measured times.
void UseBenchmarkAccuracy(Solver* solver);

/// Makes solver `name` (MakeSolver()) with `time_limit_s` per solve and the benchmark accuracy: a
/// benchmark's factory. A solver that cycles is a failed sample, not a benchmark that never ends.
SolverFactory BenchmarkSolverFactory(const std::string& name, double time_limit_s);

/// Cold: each repeat solves `program` with a fresh solver from `make` (no guess beyond the
/// program's own). The outcome is the first solve's; the time is the median of the repeats.
QpSample MeasureCold(const SolverFactory& make, const Program& program, const QpMeasureSettings& settings);

/// Identical re-solve: one solver solves `program` once (not counted), then again and again
/// from its own last solution (WarmStartFrom); the median time of the repeats.
QpSample MeasureIdenticalResolve(const SolverFactory& make, const Program& program, const QpMeasureSettings& settings);

/// A sequence of `count` problems in `*program`: before problem k, `apply(k, program)` changes its
/// data. kCold solves each with a fresh solver; kWarmSequence with one solver, each problem
/// warm-started from the previous solution (WarmStartFrom). One sample per problem.
/// kIdenticalResolve is not a sequence regime: std::invalid_argument.
std::vector<QpSample> MeasureSequence(const SolverFactory& make, SolveRegime regime, Program* program, int count,
                                      const std::function<void(int k, Program* program)>& apply);

/// A solver's record over a set in one regime, qpbenchmark style.
struct QpBenchSummary {
  int problems = 0;  ///< problems in the set
  int solved_mid = 0;   ///< solved within kMidAccuracy
  int solved_high = 0;  ///< solved within kHighAccuracy
  /// Shifted geometric mean of the CPU times [us] with shift `shift_us`; a problem not solved
  /// within kMidAccuracy counts as `failure_us` (qpbenchmark counts its time limit).
  double shifted_geomean_us = 0.0;
};

/// The shift of the shifted geometric mean here: 10 us. (qpbenchmark shifts by 10 s: its
/// problems take seconds; ours take microseconds to milliseconds, where a 10 s shift would make
/// every mean the shift and every ratio 1.)
constexpr double kGeomeanShiftUs = 10.0;

/// exp(mean(log(t + shift))) - shift; 0 for no values.
double ShiftedGeometricMean(const std::vector<double>& values, double shift);

/// Summarises samples of one solver in one regime.
QpBenchSummary Summarise(const std::vector<QpSample>& samples, double failure_us);

/// The machine a benchmark ran on, to print beside its numbers: the CPU model, the logical CPUs
/// and the load averages (Linux's /proc; "unknown" parts elsewhere).
std::string DescribeMachine();

}  // namespace stairplan::optim
