// What a solve returns: a status enum, the solution and the solve information, by value.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace stairplan::optim {

/// How a solve ended. Outcomes are reported here, never thrown.
enum class SolveStatus {
  kSolved,
  kInfeasible,
  kUnbounded,       ///< only where detectable
  kIterationLimit,
  kTimeLimit,
  kNumericalError,
  kInvalidInput,    ///< NaN in the data, or a program the solver cannot handle
};

/// "solved", "infeasible", ... (stable names used by the CLI and JSON).
std::string_view ToString(SolveStatus status);

/// Which side of a constraint is active: 0 none, -1 lower, +1 upper (equalities use -1).
using ActiveSide = std::int8_t;

/// Active constraints of a QP solution, usable as a warm start for the next solve.
struct ActiveSet {
  std::vector<ActiveSide> rows;    ///< one per linear row
  std::vector<ActiveSide> bounds;  ///< one per variable
};

/// Iterations, time and residuals of a solve.
struct SolveInfo {
  int iterations = 0;           ///< active-set changes (QP) or solver iterations (NLP)
  int outer_iterations = 0;     ///< proximal-point iterations (active-set solver on singular H)
  /// Warm starts abandoned for a cold start (active-set solver: a warm start's Infeasible or
  /// NumericalError is re-checked from cold before it is reported; CLP: any unsolved warm start).
  int cold_restarts = 0;
  double solve_time_us = 0.0;  ///< wall-clock time of the solve, measured by Solve() [us]
  double primal_residual = 0.0;  ///< max violation of rows and bounds
  double dual_residual = 0.0;    ///< inf-norm of H x + g + A'y + z (QP part)
};

/// The result of one solve. Duals follow H x + g + A' row_duals + bound_duals = 0 with a dual <= 0
/// at an active lower bound and >= 0 at an active upper bound.
struct SolveResult {
  SolveStatus status = SolveStatus::kInvalidInput;  ///< how the solve ended
  Eigen::VectorXd x;  ///< the solution (or the last iterate)
  Eigen::VectorXd row_duals;  ///< one per linear row
  Eigen::VectorXd bound_duals;  ///< one per variable
  /// The nonlinear constraints' rows' multipliers, in the program's order and with the same signs
  /// (the Lagrangian gains J' nonlinear_duals): Ipopt fills it, NLopt (no multipliers) empties it,
  /// the QP-only active-set solver leaves it alone.
  Eigen::VectorXd nonlinear_duals;
  double objective = 0.0;  ///< including the program's constant
  ActiveSet active_set;  ///< the final active set (warm-starts the next solve)
  SolveInfo info;  ///< iterations, time and residuals
  /// True when the status is kSolved.
  bool solved() const { return status == SolveStatus::kSolved; }
};

}  // namespace stairplan::optim
