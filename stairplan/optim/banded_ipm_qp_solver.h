// BandedIpmQpSolver: a primal-dual interior-point QP solver (Mehrotra's predictor-corrector)
// whose Newton systems are solved by a band Cholesky factorisation, for programs with knot
// structure such as the body planner's per-cycle QP.
//
//   min 0.5 x'Hx + g'x   s.t.  row_lower <= A x <= row_upper,  variable_lower <= x <= variable_upper
//
// Why: the body QP's variables live on knots and its costs and rows couple neighbouring knots
// only, so the reduced Newton matrix H + A'DA (+ the bounds' diagonal) is banded once the
// variables are ordered knot by knot. An interior point's cost does not depend on how many
// constraints are active (a cold active-set solve pays one factorisation update per change), and
// each of its iterations is one band factorisation: n b^2 / 2 multiply-adds for half-bandwidth b.
//
// Method (Mehrotra 1992; Wright, Primal-Dual Interior-Point Methods, 1997, chapters 10 and 11
// for the QP form): every finite side of a row or bound gets a slack s >= 0 and a multiplier
// lambda >= 0; the Newton system is reduced to (H + A'DA + D_bounds + rho I) dx = r with
// D = lambda / s per side, factorised once per iteration and solved twice (predictor, corrector).
// Equalities (lower == upper) are kept as rows with a small dual regularisation delta (the
// proximal method of multipliers' term), so they enter D as 1 / delta and need no slack pair.
// The variables are ordered by reverse Cuthill-McKee over the pattern of H + A'A (or kept in
// the program's order when that is narrower); a wide band is the dense factorisation. Once the
// active set (Tapia's indicator: sides whose slack shrinks faster than their multiplier) stops
// changing, an equality-constrained solve on it (the polish) is tried: kept when it meets the
// tolerance with duals of the right signs, it ends the solve at an active-set solver's accuracy
// a few iterations before the interior point would get there. Near the optimum (a small gap)
// it is also tried without waiting for the set to settle, each time mu has fallen a hundredfold
// (kept then only within the absolute tolerance).
//
// Outcomes: kSolved when qpbenchmark's primal residual, dual residual and duality gap are all
// within tolerance; kInfeasible when the multipliers grow into a Farkas certificate (A'y + z ~ 0
// with a negative support value); kUnbounded when the iterates run off along a direction of
// descent the constraints allow; otherwise kIterationLimit, kTimeLimit or kNumericalError.
// Duals follow SolveResult's convention. The interior point starts from its own starting point
// (it gains little from the last solution; the program's initial guess is not used). A solve
// after a solved one of the same size first tries the polish on the last solve's active set
// from its solution (settings warm_start): a control loop's next QP usually keeps the active
// set, and then one factorisation solves it (reported as 0 iterations); when the polish fails
// its checks the interior point runs as from cold. The workspace and the variable order are
// kept between solves, so a solve of a program of the same size allocates nothing (storage only
// grows with the band and nonzeros).
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "stairplan/optim/band_cholesky.h"
#include "stairplan/optim/band_ordering.h"
#include "stairplan/optim/packed_rows.h"
#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// Settings of BandedIpmQpSolver.
struct BandedIpmQpSettings {
  /// Interior-point iterations allowed per solve.
  int max_iterations = 100;
  /// Wall-clock limit per solve [s], checked every iteration. Infinity means none.
  double time_limit_s = kInf;
  /// Solved when the primal residual, dual residual and duality gap (qpbenchmark's) are each at
  /// most tolerance + relative_tolerance * (the size of the terms they are made of).
  double tolerance = 1e-9;
  /// See tolerance: the round-off floor of programs with large terms (objectives of 1e7, where
  /// the gap's terms cancel to about 1e-16 of their size) lets them finish.
  double relative_tolerance = 1e-15;
  /// Primal regularisation rho on the Newton matrix's diagonal (keeps LPs and singular H
  /// factorisable; the residuals are the unregularised problem's, so the solution is not moved).
  double primal_regularization = 1e-9;
  /// Dual regularisation delta of the equalities.
  double equality_regularization = 1e-9;
  /// Fraction of the way to the boundary of s, lambda >= 0 an iteration goes at most.
  double step_fraction = 0.995;
  /// Iterative-refinement steps per Newton solve (against the regularised reduced matrix). None
  /// by default: an interior point corrects an inexact step at the next iteration, and the final
  /// accuracy comes from the polish on the active set.
  int refinement_steps = 0;
  /// Try the last solve's active set first when the last solve was solved and the program has
  /// the same size (see the file's top comment); off: every solve runs the interior point.
  bool warm_start = true;
  /// Throws std::invalid_argument naming the offending field.
  void Validate() const;
};

/// Mehrotra predictor-corrector interior point over a band Cholesky (see the file's top comment).
class BandedIpmQpSolver final : public Solver {
 public:
  BandedIpmQpSolver() = default;
  /// With `settings` (checked: throws std::invalid_argument naming the field).
  explicit BandedIpmQpSolver(const BandedIpmQpSettings& settings) : settings_(settings) { settings_.Validate(); }

  std::string_view name() const override { return "banded-ipm"; }
  /// Quadratic programs only (no nonlinear costs or constraints).
  bool Supports(const Program& program) const override { return program.IsQuadratic(); }

  ///@{
  /// The settings, changeable between solves.
  BandedIpmQpSettings& settings() { return settings_; }
  const BandedIpmQpSettings& settings() const { return settings_; }
  ///@}

  /// The half-bandwidth of the last solve's Newton matrix in the order it was factorised in.
  int bandwidth() const { return factor_.bandwidth(); }
  /// True when the last solve reordered the variables (reverse Cuthill-McKee).
  bool reordered() const { return ordering_.reordered(); }
  /// True when the last solve was solved by the polish on the active set of the solve before
  /// (settings warm_start), without interior-point iterations.
  bool warm_started() const { return warm_started_; }

 private:
  void DoSolve(const Program& program, SolveResult* result) override;

  // Sizing, the sparse copies of H and A (when their revisions changed), the bounds; false when
  // the size changed (the last solve's iterate means nothing then).
  bool Prepare(const Program& program);
  // This solve's sides and equalities from the program's bounds.
  void LoadBounds(const Program& program);
  // The variable order and band from the pattern of H + A'A.
  void Analyse();
  // Per constraint, a_k'x for every k.
  void ComputeValues(const Eigen::VectorXd& x, Eigen::VectorXd* values) const;
  // qpbenchmark's measures of a point (x, y) and the sizes of their terms (for the relative
  // tolerance); values, H x and the dual residual into the given vectors.
  struct Measures {
    double primal = 0.0, dual = 0.0, gap = 0.0;
    double primal_scale = 0.0, dual_scale = 0.0, gap_scale = 0.0;
    double support = 0.0, combination = 0.0;  // the gap's support term; |A'y + z|_inf
  };
  Measures Measure(const Eigen::VectorXd& x, const Eigen::VectorXd& y, Eigen::VectorXd* values, Eigen::VectorXd* hx,
                   Eigen::VectorXd* r_dual) const;
  // Only the vectors of Measure(): values, H x and the dual residual.
  void Residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& y, Eigen::VectorXd* values, Eigen::VectorXd* hx,
                 Eigen::VectorXd* r_dual) const;
  // The iterate's duals, residuals, complementarity and measures.
  void ComputeResiduals();
  bool Converged(const Measures& measures) const;
  // The duality gap small beside its terms (see kEarlyPolishGap in the .cc): when the polish
  // is worth trying on a set that has not settled.
  bool NearOptimum(const Measures& measures) const;
  // Converged() without the relative tolerance.
  bool ConvergedAbsolute(const Measures& measures) const;
  // The active-set polish (see Polish() in the .cc); true when it solved the program. `strict`:
  // kept only within the absolute tolerance (Converged() without its relative part).
  bool Polish(bool strict = false);
  // After the polish's first step: a multiplier of the wrong sign or an inactive constraint
  // violated beyond round-off (see the .cc), which the remaining steps cannot mend.
  bool ClearlyWrongSet() const;
  // The sides the iterate holds active (multiplier above slack) into active_; returns how many
  // constraints changed side.
  int UpdateActiveSides();
  bool IsInfeasible() const;
  bool IsUnbounded() const;
  // D from the iterate, then the Newton matrix H + rho I + sum D_k a_k a_k' assembled in band
  // storage and factorised.
  void Factorize();
  void Assemble();
  // K dx = rhs_ into dx_ through the factor, with refinement against K.
  void SolveReduced();
  void SolveThroughFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd* solution);
  void MultiplyReduced(const Eigen::VectorXd& v, Eigen::VectorXd* out) const;
  // The Newton direction for the complementarity targets rc_ (per side).
  void Direction();
  // Largest step keeping s and lambda nonnegative along the current direction (infinite: none).
  double MaxStep() const;
  // The mean complementarity after a step of alpha along the current direction.
  double ComplementarityAfter(double alpha) const;
  void Step(double alpha);
  // The start (see StartingPoint() in the .cc).
  void StartingPoint();
  // The polish on the last solve's active set, from its solution (see warm_start); true when it
  // solved the program.
  bool WarmPolish();
  SolveStatus Iterate();
  void FillResult(const Program& program, SolveStatus status, SolveResult* result) const;

  // Constraint k: k < m is row k of A, k >= m bounds variable k - m.
  void AddNormal(int k, double alpha, Eigen::VectorXd* y) const {
    if (k < m_) {
      rows_.AddRow(k, alpha, y);
    } else {
      (*y)[k - m_] += alpha;
    }
  }

  BandedIpmQpSettings settings_;
  const Program* program_ = nullptr;
  int n_ = 0, m_ = 0;
  bool bounds_consistent_ = true;  // no lower bound above its upper one

  std::uint64_t hessian_revision_ = 0, matrix_revision_ = 0;
  bool analysed_ = false;
  PackedRows rows_, hessian_rows_;
  PackedRows columns_;  // A's columns, for the products A'y (rows_ for A x)
  BandOrdering ordering_;
  BandCholesky factor_;
  // Assemble()'s places, from Analyse(): H's lower triangle in band storage, each variable's
  // diagonal slot, and per row (ending at pair_end_[k]) the slots and products a_ke a_kf of its
  // pairs of nonzeros in the lower triangle.
  std::vector<double> h_band_;
  std::vector<int> diagonal_slot_, pair_slot_, pair_end_;
  std::vector<double> pair_product_;

  // Per constraint (rows, then variables): the bounds (+-inf: none); the same with 0 for an
  // infinite one, and 1 where either is finite (0 elsewhere).
  Eigen::VectorXd lower_, upper_, finite_lower_, finite_upper_, bounded_;
  // Each finite inequality side j (a two-sided constraint has two): its constraint, its sign
  // (+1 lower: s = v - bound, -1 upper: s = bound - v) and bound, so that s = sign (v - bound).
  // The per-side vectors are sized for every constraint's two sides; the first sides_ are used.
  int sides_ = 0;
  std::vector<int> side_constraint_;
  Eigen::VectorXd side_sign_, side_bound_;
  // The equalities (lower == upper), by constraint.
  std::vector<int> equalities_;

  // The iterate: x, per side the slack s and multiplier l, per constraint the equality
  // multipliers w (zero elsewhere).
  Eigen::VectorXd x_, s_, l_, w_;
  // Per side 1 / s and 1 / l (at the last factorisation), the residual sign (v - bound) - s,
  // the complementarity targets and the step; whether the last step changed the multiplier
  // relatively more than the slack (the side is active by Tapia's indicator).
  Eigen::VectorXd inverse_s_, inverse_l_, r_, rc_, ds_, dl_;
  std::vector<int> multiplier_leads_;
  double step_rate_ = 0.0;  // the last direction's fastest relative decrease of a slack or multiplier
  // Per constraint: values v = a_k'x, D, the right-hand side's term e, the step's dv and dw, the
  // duals in SolveResult's convention. Per variable: H x, the dual residual H x + g + A'y + z.
  Eigen::VectorXd v_, d_, e_, dv_, dw_, y_, hx_, r_dual_;
  Eigen::VectorXd rhs_, dx_, work_, correction_, permuted_;
  // The iterate's active set (the polish's when it succeeded), and the polish's point, duals
  // and targets.
  std::vector<ActiveSide> active_, previous_active_;
  Eigen::VectorXd xp_, yp_, vp_, hxp_, rdp_, target_;
  Measures measures_, polish_measures_;
  double next_polish_mu_ = kInf;
  // mu at or below which the polish is tried on a set that has not settled (see Iterate()).
  double early_polish_mu_ = 0.0;
  // The last solve ended solved (its x_, y_ and active_ are a warm start's guess).
  bool last_solved_ = false;
  // Whether the last solve ended in the polish of the solve before's active set.
  bool warm_started_ = false;
  double mu_ = 0.0;
  double rho_ = 0.0, delta_ = 0.0;
  int iterations_ = 0;
  std::chrono::steady_clock::time_point deadline_;
  bool has_deadline_ = false;
};

}  // namespace stairplan::optim
