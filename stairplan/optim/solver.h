// Solver: the small interface every back-end implements (Drake style: a public checked Solve()
// calling a private DoSolve()).
//
// Usage:
//   Program prog = ...;                       // built once
//   ActiveSetQpSolver qp;                     // or IpoptSolver, NloptSolver, MakeSolver(prog) (solvers/)
//   qp.settings().time_limit_s = 0.002;       // typed settings with documented defaults
//   SolveResult result;
//   qp.Solve(prog, &result);                  // reuses result's storage: no allocation once sized
//   if (result.solved()) Use(result.x);
//   SolveResult copy = qp.Solve(prog);        // by value, for code that is not per-cycle
//
// Solve() checks the program (NaN anywhere gives kInvalidInput; a nonlinear program given to a
// QP-only solver gives kInvalidInput) and measures the solve time; DoSolve() does the work.
#pragma once

#include <string_view>

#include "stairplan/optim/program.h"
#include "stairplan/optim/solve_result.h"

namespace stairplan::optim {

/// The interface every solver back-end implements: a checked public Solve() over a private DoSolve().
class Solver {
 public:
  virtual ~Solver() = default;

  /// Solves `program` into `result`, reusing its vectors (allocation-free once they have the size).
  void Solve(const Program& program, SolveResult* result);
  /// Solves `program` and returns a fresh result.
  SolveResult Solve(const Program& program);

  /// A short name: "active-set", "banded-ipm", "ipopt", "nlopt", "clp", "clp-barrier".
  virtual std::string_view name() const = 0;
  /// True when this solver handles programs of this kind (e.g. QP-only solvers refuse nonlinear ones).
  virtual bool Supports(const Program& program) const = 0;

 private:
  virtual void DoSolve(const Program& program, SolveResult* result) = 0;
  /// Checks the data for NaN, skipping the matrices when their revisions were already checked.
  bool DataIsValid(const Program& program);

  std::uint64_t checked_hessian_revision_ = 0;
  std::uint64_t checked_matrix_revision_ = 0;
  std::uint64_t checked_whole_matrix_revision_ = 0;
};

}  // namespace stairplan::optim
