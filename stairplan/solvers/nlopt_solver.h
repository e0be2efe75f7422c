// NloptSolver: NLopt's SLSQP for smooth NLPs, or a derivative-free algorithm (COBYLA) on request.
//
// Linear rows and nonlinear constraints become NLopt inequality (c(x) <= 0) and equality
// constraints; variable bounds are passed as bounds. NLopt returns no multipliers, so the duals
// in the result are zero. NLopt allocates: this is an offline and cross-checking solver.
#pragma once

#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// Settings of NloptSolver.
struct NloptSettings {
  /// NLopt's algorithm.
  enum class Algorithm { kSlsqp, kCobyla };
  /// kSlsqp (gradient based, default) or kCobyla (derivative-free).
  Algorithm algorithm = Algorithm::kSlsqp;
  ///@{
  /// Relative tolerance on x and on f between iterations.
  double xtol_rel = 1e-10;
  double ftol_rel = 1e-14;
  ///@}
  /// Violation NLopt accepts when it keeps its best point. Tighter values make SLSQP keep an
  /// early feasible iterate instead of its (slightly infeasible) converged one: on HS100, 1e-8
  /// gives 690.6 where 1e-6 gives the optimum 680.6300573 to 1e-10.
  double constraint_tol = 1e-6;
  /// Function evaluations allowed.
  int max_evaluations = 100000;
  /// Solve in variables scaled by 1 / sqrt of the objective's Hessian diagonal at the initial
  /// guess (quadratic part plus the nonlinear costs' Hessian callbacks): SLSQP's quasi-Newton
  /// matrix starts as the identity, far from a badly scaled problem's curvature.
  bool scale_by_hessian = false;
  /// Wall-clock limit per solve [s]. Infinity means none.
  double time_limit_s = kInf;
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// NLopt (SLSQP, or COBYLA on request) for smooth NLPs: an offline and cross-checking solver.
class NloptSolver final : public Solver {
 public:
  NloptSolver() = default;
  /// With `settings` (checked: throws std::invalid_argument naming the field).
  explicit NloptSolver(const NloptSettings& settings) : settings_(settings) { settings_.Validate(); }

  std::string_view name() const override { return "nlopt"; }
  bool Supports(const Program&) const override { return true; }

  ///@{
  /// The settings, changeable between solves.
  NloptSettings& settings() { return settings_; }
  const NloptSettings& settings() const { return settings_; }
  ///@}

 private:
  void DoSolve(const Program& program, SolveResult* result) override;

  NloptSettings settings_;
};

}  // namespace stairplan::optim
