// IpoptSolver: any Program (nonlinear included) through Ipopt 3.11's TNLP interface.
//
// QPs get the exact (constant) Hessian; so do programs whose every nonlinear cost and constraint
// has a Hessian callback (the Lagrangian's Hessian from them and the quadratic part); the others
// use Ipopt's limited-memory quasi-Newton Hessian. Options pass through by name. The time limit is a wall-clock deadline
// checked in Ipopt's per-iteration callback on every solve (and also passed as max_cpu_time), so
// it holds for the second solve as for the first. A fresh IpoptApplication per solve keeps solves
// independent; Ipopt allocates, so this is not the per-cycle solver.
//
// Warm starts: the program's initial guess is always the starting point; a dual guess (a previous
// result's multipliers mapped onto this program) makes Ipopt start from those multipliers too
// (warm_start_init_point), which is what cuts a re-solve of a shifted problem to a few iterations.
// Ipopt then pushes the start into the interior by warm_start_bound_push / warm_start_mult_bound_push
// (1e-3 by default, which undoes much of a warm start: set them small through numeric_options).
#pragma once

#include <map>
#include <string>

#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// Settings of IpoptSolver.
struct IpoptSettings {
  /// Ipopt's "tol" (scaled NLP error).
  double tolerance = 1e-9;
  /// Ipopt's "max_iter".
  int max_iterations = 3000;
  /// Wall-clock limit per solve [s]. Infinity means none.
  double time_limit_s = kInf;
  /// Use the exact Hessian for quadratic programs.
  bool exact_hessian_for_qp = true;
  /// Use the exact Hessian of the Lagrangian for nonlinear programs when every nonlinear part has
  /// a Hessian callback (Program::HasHessians()); limited-memory otherwise or when false.
  bool exact_hessian_for_nlp = true;
  ///@{
  /// Options passed through to Ipopt as they are (set after the ones above, so they win).
  std::map<std::string, std::string> string_options;
  std::map<std::string, double> numeric_options;
  std::map<std::string, int> integer_options;
  ///@}
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// Multipliers to start from, with SolveResult's signs: a dual <= 0 on an active lower side, >= 0
/// on an active upper side (an inactive one 0).
struct IpoptDualGuess {
  Eigen::VectorXd row_duals;        ///< one per linear row
  Eigen::VectorXd nonlinear_duals;  ///< one per nonlinear constraint row
  Eigen::VectorXd bound_duals;      ///< one per variable
};

/// Ipopt (interior point) for QPs and NLPs: the reference solver and the NLP back-end.
class IpoptSolver final : public Solver {
 public:
  IpoptSolver() = default;
  /// With `settings` (checked: throws std::invalid_argument naming the field).
  explicit IpoptSolver(const IpoptSettings& settings) : settings_(settings) { settings_.Validate(); }

  std::string_view name() const override { return "ipopt"; }
  bool Supports(const Program&) const override { return true; }

  ///@{
  /// The settings, changeable between solves.
  IpoptSettings& settings() { return settings_; }
  const IpoptSettings& settings() const { return settings_; }
  ///@}

  /// Starts the next solves from these multipliers (and the program's initial guess) until
  /// ClearDualGuess(). Solve() throws std::invalid_argument naming the field whose size does not
  /// match the program's rows or variables.
  void SetDualGuess(IpoptDualGuess guess);
  /// Solves start from the program's initial guess alone again.
  void ClearDualGuess() { has_dual_guess_ = false; }
  /// True while a dual guess is set.
  bool has_dual_guess() const { return has_dual_guess_; }

 private:
  void DoSolve(const Program& program, SolveResult* result) override;
  void CheckDualGuess(const Program& program) const;

  IpoptSettings settings_;
  IpoptDualGuess dual_guess_;
  bool has_dual_guess_ = false;
};

}  // namespace stairplan::optim
