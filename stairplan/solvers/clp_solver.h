// ClpSolver: quadratic programs through COIN-OR CLP 1.17 (Debian's coinor-libclp-dev), the second
// QP reference beside Ipopt: its primal simplex for QPs (ClpSimplex::primal with a quadratic
// objective, unscaled) or its barrier (ClpSolve's useBarrier: presolve, ClpInterior).
//
// Whether CLP is there is decided in CMake: clp_solver.cc when pkg-config finds `clp`,
// clp_solver_unavailable.cc otherwise (IsAvailable() false, Supports() false, so Solve() reports
// kInvalidInput, and MakeSolver("clp") throws naming the missing package).
//
// Warm starts: every solve loads the program into a fresh CLP model and, when the last solve at
// the same size was solved, starts the simplex from its basis and solution, and solves again from
// cold when that start fails. (Changing bounds and costs in a kept model, CLP's own hot start,
// returned points off the optimum on the crane sequence.) ResetWarmStart() or warm_start = false starts from CLP's crash basis; the barrier
// always starts cold. CLP allocates: a reference for benchmarks and cross-checks, not a
// per-cycle solver.
//
// Duals follow SolveResult's convention (H x + g + A' row_duals + bound_duals = 0): CLP's row
// duals and reduced costs with their sign flipped. The active set is read from the duals' signs.
#pragma once

#include <memory>

#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// CLP's algorithm for QPs.
enum class ClpAlgorithm {
  kPrimalSimplex,  ///< ClpSimplex::primal (reduced-gradient simplex for the quadratic objective)
  kBarrier,        ///< ClpSimplex::initialSolve with ClpSolve::useBarrier: presolve, ClpInterior
};

/// Settings of ClpSolver.
struct ClpSettings {
  ClpAlgorithm algorithm = ClpAlgorithm::kPrimalSimplex;  ///< primal simplex or barrier
  /// CLP's primal feasibility tolerance (CLP's default 1e-7; tighter so that solutions meet 1e-9).
  double primal_tolerance = 1e-9;
  /// CLP's dual feasibility tolerance (CLP's default 1e-7).
  double dual_tolerance = 1e-9;
  /// CLP's iteration limit per solve.
  int max_iterations = 1000000;
  /// Time limit per solve [s] on CLP's own clock. Infinity means none.
  double time_limit_s = kInf;
  /// Start each solve from the previous solve's basis and solution (simplex only).
  bool warm_start = true;
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// COIN-OR CLP as a second QP reference (see the file's top comment); optional in the build.
class ClpSolver final : public Solver {
 public:
  ClpSolver();
  /// With `settings` (checked: throws std::invalid_argument naming the field).
  explicit ClpSolver(const ClpSettings& settings);
  ~ClpSolver() override;
  ClpSolver(const ClpSolver&) = delete;
  ClpSolver& operator=(const ClpSolver&) = delete;

  /// True when stairplan was built with CLP.
  static bool IsAvailable();

  /// "clp" (primal simplex) or "clp-barrier".
  std::string_view name() const override;
  /// Quadratic programs only, and only when CLP is available.
  bool Supports(const Program& program) const override { return IsAvailable() && program.IsQuadratic(); }

  ///@{
  /// The settings, changeable between solves.
  ClpSettings& settings() { return settings_; }
  const ClpSettings& settings() const { return settings_; }
  ///@}

  /// The next solve starts from CLP's crash basis.
  void ResetWarmStart();

 private:
  void DoSolve(const Program& program, SolveResult* result) override;
  struct Model;  // CLP's objects, kept out of this header
  // Reads CLP's solution into `result` and keeps the basis for the next warm start.
  void FillResult(const Program& program, Model& model, SolveResult* result);
  // CLP's objects, kept out of this header
  ClpSettings settings_;
  std::unique_ptr<Model> model_;
};

}  // namespace stairplan::optim
