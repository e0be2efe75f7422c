// ActiveSetQpSolver: our per-cycle QP solver, a dense dual active-set method of the
// Goldfarb-Idnani family, built for repeated solves of one Program.
//
// Why this shape: the body planner solves the same QP structure every 3 ms with new bounds and
// linear terms. The solver keeps the Cholesky factor of H and the QR-like factorisation (J, R) of
// the active constraints between solves, so a re-solve starts from the previous active set in
// O(n^2) and only pays for the active-set changes. Nothing is allocated after the first solve at
// a given size (tests/optim/qp_allocation_test.cc counts it).
//
//   ActiveSetQpSolver solver;             // one per planner, lives as long as the Program
//   SolveResult result;
//   solver.Solve(program, &result);       // first solve: factorises H, sizes the workspace
//   program.SetVariableBounds(block, lo, hi);
//   solver.Solve(program, &result);       // hot: last active set and factorisation, no allocation
//   program.SetConstraintCoefficients(rows, block, coeffs);
//   solver.Solve(program, &result);       // still hot: changed rows that were active are dropped
//   program.MutableConstraintMatrix() = A;
//   solver.Solve(program, &result);       // warm: A replaced, refactorised from the last active set
//   solver.SetWarmStart(saved.active_set); // or start from any stored active set
//   solver.ResetWarmStart();              // or cold
//
// Positive semidefinite H: proximal-point outer iterations
//   x_{k+1} = argmin 0.5 x'Hx + g'x + rho/2 |x - x_k|^2  s.t. constraints,
// each warm-started from the previous active set and factorisation (H + rho I does not change),
// until the step is tiny; LP-like problems solve too. Dependent equality rows are detected while
// factorising and skipped when consistent. Bounds at or beyond 1e20 in magnitude mean none.
#pragma once

#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "stairplan/optim/solver.h"
#include "stairplan/optim/sparse_rows.h"

namespace stairplan::optim {

/// Settings of ActiveSetQpSolver (the defaults suit both per-cycle use and the test sets).
struct ActiveSetQpSettings {
  /// Active-set changes allowed per solve (over all proximal iterations).
  int max_iterations = 100000;
  /// Proximal-point iterations allowed when H is singular.
  int max_outer_iterations = 2000;
  /// Wall-clock limit per solve [s]; checked inside the iteration loop. Infinity means none.
  double time_limit_s = kInf;
  /// A constraint counts as violated beyond feasibility_tol * (1 + |bound|). One that the active
  /// constraints pin beyond its bound by round-off alone, at a degenerate vertex (up to 1e-6
  /// relative), counts as met: the result is kSolved with that residual, not kInfeasible.
  double feasibility_tol = 1e-9;
  /// Proximal weight relative to max(1, max |H_ii|), used when H is singular.
  double proximal_weight = 1e-7;
  /// Proximal iterations stop when |x_{k+1} - x_k|_inf <= proximal_tol * (1 + |x|_inf).
  double proximal_tol = 1e-11;
  /// ... or when the remaining dual residual rho |x_{k+1} - x_k| times (1 + |x|_inf) is below
  /// proximal_objective_tol * (1 + |objective|): it can no longer move the objective noticeably.
  double proximal_objective_tol = 1e-10;
  /// Iterative-refinement steps on the final active set (each kept only if it lowers the KKT
  /// residuals; none once they are below 1e-12 absolute). Each costs about
  /// two products with the n x n factor: off for per-cycle use; kHighAccuracyRefinementSteps for
  /// qpbenchmark's 1e-9 absolute residuals on badly scaled problems.
  int refinement_steps = 0;
  /// refinement_steps for qpbenchmark-style accuracy (`qp bench`).
  static constexpr int kHighAccuracyRefinementSteps = 3;
  /// Start each solve from the previous solve's active set and factorisation.
  bool warm_start = true;
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// Our dense dual active-set QP solver (see the file's top comment): the per-cycle solver, warm-started.
class ActiveSetQpSolver final : public Solver {
 public:
  ActiveSetQpSolver() = default;
  /// With `settings` (checked: throws std::invalid_argument naming the field).
  explicit ActiveSetQpSolver(const ActiveSetQpSettings& settings) : settings_(settings) { settings_.Validate(); }

  std::string_view name() const override { return "active-set"; }
  /// Quadratic programs only (no nonlinear costs or constraints).
  bool Supports(const Program& program) const override { return program.IsQuadratic(); }

  ///@{
  /// The settings, changeable between solves.
  ActiveSetQpSettings& settings() { return settings_; }
  const ActiveSetQpSettings& settings() const { return settings_; }
  ///@}

  /// The next solve starts from this active set (sizes must match the program then).
  void SetWarmStart(const ActiveSet& active_set);
  /// The next solve starts cold (from the unconstrained minimum).
  void ResetWarmStart() { factorization_valid_ = false; pending_warm_start_ = false; }

 private:
  void DoSolve(const Program& program, SolveResult* result) override;

  // Workspace sizing and the factorisation of H (+ rho I), reused while H is unchanged.
  void Prepare(const Program& program);
  bool FactorizeHessian(const Program& program);
  // H's diagonal blocks (j0_first_), read from its zeros once per Hessian.
  void FindHessianBlocks(const Eigen::MatrixXd& h);
  // Whether dropping the active rows `program` changed since the last solve and adding them back
  // takes fewer rotations than rebuilding the factorisation from the whole active set.
  bool ReaddCheaperThanRebuild(const Program& program) const;
  // Starting points: cold, from a given active set, or the kept factorisation.
  void StartCold();
  void StartFromActiveSet(const ActiveSet& set);
  // From the kept factorisation to `set`: drops the active constraints `set` does not hold (on
  // that side), then adds the ones it holds that are not active.
  void MoveToActiveSet(const ActiveSet& set);
  // Rotations of `adds` constraint additions from q active ones.
  long AddCost(int q, int adds) const;
  // Adds the constraints `set` holds that are not active (a finite bound on their side).
  void AddActive(const ActiveSet& set);
  // The side of constraint k in `set` (0 beyond its size).
  ActiveSide SideIn(const ActiveSet& set, int k) const;
  void AddEqualities();
  // Closed-form primal and dual on the current active set; drops constraints with negative
  // multipliers until the start is dual feasible. Returns the number of drops.
  int Restart();
  // The closed form on the active set from tmp_ = J' g: multipliers (and R^{-T} b in r_), then x.
  void ComputeMultipliers();
  void ComputePrimal();
  // The proximal (if regularized) and polishing loops around Iterate() from the current start.
  SolveStatus Run(bool regularized, int* outer_iterations);
  // The Goldfarb-Idnani loop from a dual-feasible start.
  SolveStatus Iterate();
  // Iterative refinement on the final active set against the original H and g: the residuals of
  // the active set's KKT system, corrected through the kept factorisation.
  double ActiveResiduals();
  void Refine();
  // Factorisation updates.
  void ComputeStepVector(int k, double sigma);  // d_ = J' (sigma n_k)
  bool AddConstraint(int k, int side);
  // Givens rotation of J's columns i and j over the rows either can be nonzero in.
  void RotateJ(int i, int j, double c, double s);
  void DropConstraint(int position);

  // Constraint k: k < m is row k of A, k >= m bounds variable k - m.
  double Lower(int k) const { return lower_[k]; }
  double Upper(int k) const { return upper_[k]; }
  // Copies this solve's bounds into lower_/upper_ and lists the bounded constraints and equalities.
  void LoadBounds(const Program& program);
  double Value(int k) const;
  double RowValue(int k) const;
  bool IsEquality(int k) const { return Lower(k) == Upper(k); }
  bool OverLimits();
  // After a proximal step: does the step direction prove the problem unbounded?
  bool IsUnboundedRay();
  // Whether x_ (with ax_ = A x_) keeps every bound (of the inactive constraints only, or of all)
  // to within relative_tol * (1 + |bound|); a NaN value counts as within.
  bool MeetsBounds(double relative_tol, bool inactive_only) const;
  void FillResult(const Program& program, SolveStatus status, SolveResult* result);

  ActiveSetQpSettings settings_;
  const Program* program_ = nullptr;
  int n_ = 0, m_ = 0;

  // Cached factorisation of H + rho I: J0 = L^{-T}.
  std::uint64_t hessian_revision_ = 0;
  std::uint64_t matrix_revision_ = 0;
  std::uint64_t whole_matrix_revision_ = 0;
  double rho_ = 0.0;
  Eigen::MatrixXd hessian_reg_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd J0_;
  // Per column of J0 (= L^{-T}): the first row of its diagonal block of H, above which it is zero.
  std::vector<int> j0_first_;

  // Active-set state: J = L^{-T} Q, upper triangular R, active constraints with their multipliers.
  bool factorization_valid_ = false;
  bool pending_warm_start_ = false;
  bool has_previous_ = false;  // state_ holds the last solve's active set for this size
  ActiveSet warm_start_;
  Eigen::MatrixXd J_, R_;
  // Per column of J: the rows [begin, end) outside which it is exactly zero (J0's zeros, kept
  // through the rotations), so that a rotation skips them.
  std::vector<int> column_begin_, column_end_;
  std::vector<int> active_;
  std::vector<ActiveSide> state_;  // per constraint: 0, -1 lower active, +1 upper active
  // Per constraint: set aside for the rest of this Iterate() as met (a degenerate vertex's
  // round-off, see Iterate()).
  std::vector<char> set_aside_;
  int q_ = 0;
  Eigen::VectorXd u_;

  // The nonzeros of A and H by row (the products below use them, not the dense matrices).
  SparseRows rows_, hessian_rows_;
  // This solve's bounds per constraint (rows, then variables); the constraints with a finite
  // bound, and the equalities, in index order.
  Eigen::VectorXd lower_, upper_;
  std::vector<int> bounded_, equalities_;
  std::vector<std::pair<int, ActiveSide>> readd_;  // changed active rows and their sides

  // Vectors of size n or m.
  Eigen::VectorXd x_, g_eff_, x_prox_, d_, z_, r_, tmp_, hx_;
  Eigen::VectorXd ax_, row_norm_;
  // Refinement: KKT residuals (dual, then per active constraint) and the point they belong to.
  Eigen::VectorXd dual_residual_, active_residual_, saved_x_, saved_u_;

  int iterations_ = 0;
  std::chrono::steady_clock::time_point deadline_;
  bool has_deadline_ = false;
  bool time_exceeded_ = false;
};

}  // namespace stairplan::optim
