// Mehrotra's predictor-corrector interior point for QPs with two-sided rows and bounds, the
// Newton system reduced to the variables and factorised in band storage.
//
// Notation: constraint k has normal a_k (row k of A, or e_j for a bound on variable j) and value
// v_k = a_k'x. Each finite inequality side j of constraint k(j) has a sign (+1 lower, -1 upper),
// a slack s_j = sign (v - bound) >= 0 and a multiplier l_j >= 0; an equality has a free
// multiplier w. The dual of constraint k in SolveResult's convention is y_k = -sum sign_j l_j
// over its sides (or w), so that the stationarity residual is r_d = H x + g + sum_k a_k y_k.
// Eliminating the slacks' and multipliers' steps from the Newton equations leaves
//   (H + rho I + sum_k D_k a_k a_k') dx = -r_d - sum_k e_k a_k
// with D_k the sum of l_j / s_j over its sides (1 / delta for an equality) and e_k from the
// residuals and the complementarity targets (Direction()). Everything per side runs over
// contiguous vectors; only D, e and the values are per constraint.
#include "stairplan/optim/banded_ipm_qp_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stairplan/optim/qp_residuals.h"

namespace stairplan::optim {
namespace {

// Pivots at or below this times the largest diagonal entry are singular directions.
constexpr double kPivotTol = 1e-18;
// A pattern with more coupled pairs than this times n^2 is factorised dense, unordered: ordering
// it would cost more than it can save.
constexpr double kDenseEdgeFraction = 0.25;
// Multipliers this much larger than the gradient H x + g make a Farkas certificate worth checking,
// and it holds when A'y + z is within kCombinationTol of |y| and the support value below
// -kCertificateTol |y|.
constexpr double kLargeDualRatio = 1e6;
constexpr double kCertificateTol = 1e-6;
// A'y + z of a Farkas certificate must vanish to this fraction of |y|: multipliers running off
// near mu = 0 on a feasible program (QPCBOEI2) come within 3e-7 of it.
constexpr double kCombinationTol = 1e-9;
// Refinement steps of the polish, and how much mu must fall before a failed polish is retried.
// (Three steps take the regularised system's error, about delta times the multipliers, below
// round-off; the polish's own measures decide whether it is kept.)
constexpr int kPolishSteps = 3;
constexpr double kPolishProgress = 1e-2;
// The polish is tried on a set that has not settled only when the duality gap is at most this
// fraction of its terms: far from the optimum the set is a guess, and a failed try costs about
// half an iteration.
constexpr double kEarlyPolishGap = 1e-3;
// Such a polish stops after its first step when a multiplier has the wrong sign or an inactive
// constraint is violated by this much relative to their size (ClearlyWrongSet()).
constexpr double kWrongSetMargin = 1e-6;
// Iterates beyond this size make a ray of unboundedness worth checking.
constexpr double kLargePrimal = 1e8;

}  // namespace

void BandedIpmQpSettings::Validate() const {
  const auto fail = [](const std::string& field) {
    throw std::invalid_argument("BandedIpmQpSettings::" + field + " is out of range");
  };
  if (max_iterations <= 0) fail("max_iterations");
  if (!(time_limit_s > 0)) fail("time_limit_s");
  if (!(tolerance > 0 && tolerance < 1)) fail("tolerance");
  if (!(relative_tolerance >= 0 && relative_tolerance < 1)) fail("relative_tolerance");
  if (!(primal_regularization > 0 && primal_regularization < 1)) fail("primal_regularization");
  if (!(equality_regularization > 0 && equality_regularization < 1)) fail("equality_regularization");
  if (!(step_fraction > 0 && step_fraction < 1)) fail("step_fraction");
  if (refinement_steps < 0) fail("refinement_steps");
}

void BandedIpmQpSolver::DoSolve(const Program& program, SolveResult* result) {
  settings_.Validate();
  has_deadline_ = std::isfinite(settings_.time_limit_s);
  if (has_deadline_) {
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                    std::chrono::duration<double>(settings_.time_limit_s));
  }
  const bool warm = Prepare(program) && settings_.warm_start && last_solved_;
  iterations_ = 0;
  next_polish_mu_ = kInf;
  warm_started_ = false;
  SolveStatus status = SolveStatus::kInfeasible;
  if (bounds_consistent_ && warm && WarmPolish()) {
    warm_started_ = true;
    status = SolveStatus::kSolved;
  } else if (bounds_consistent_) {
    std::fill(active_.begin(), active_.end(), ActiveSide{0});
    StartingPoint();
    status = Iterate();
  } else {
    x_.setZero();
    s_.setZero();
    l_.setZero();
    w_.setZero();
    ComputeResiduals();
  }
  last_solved_ = status == SolveStatus::kSolved;
  FillResult(program, status, result);
}

bool BandedIpmQpSolver::WarmPolish() {
  // The last active set, less the sides this program no longer has; its equalities as they are now.
  for (int k = 0; k < n_ + m_; ++k) {
    ActiveSide& side = active_[static_cast<std::size_t>(k)];
    if ((side < 0 && !std::isfinite(lower_[k])) || (side > 0 && !std::isfinite(upper_[k]))) side = 0;
    if (lower_[k] == upper_[k]) side = -1;
    if (side == 0) y_[k] = 0.0;
  }
  return Polish();
}

bool BandedIpmQpSolver::Prepare(const Program& program) {
  const int n = program.num_variables(), m = program.num_rows();
  const bool resized = n != n_ || m != m_ || program_ == nullptr;
  const bool other = &program != program_;
  program_ = &program;
  if (resized) {
    n_ = n;
    m_ = m;
    const int k = n + m;
    for (Eigen::VectorXd* v : {&lower_, &upper_, &finite_lower_, &finite_upper_, &bounded_, &w_, &v_, &d_, &e_,
                               &dv_, &dw_, &y_, &yp_, &vp_, &target_}) {
      v->resize(k);
    }
    for (Eigen::VectorXd* v :
         {&side_sign_, &side_bound_, &s_, &l_, &inverse_s_, &inverse_l_, &r_, &rc_, &ds_, &dl_}) {
      v->resize(2 * k);
    }
    for (Eigen::VectorXd* v :
         {&x_, &r_dual_, &hx_, &rhs_, &dx_, &work_, &correction_, &permuted_, &xp_, &hxp_, &rdp_}) {
      v->resize(n);
    }
    side_constraint_.resize(2 * static_cast<std::size_t>(k));
    multiplier_leads_.resize(2 * static_cast<std::size_t>(k));
    equalities_.reserve(static_cast<std::size_t>(k));
    active_.assign(static_cast<std::size_t>(k), 0);
    previous_active_.assign(static_cast<std::size_t>(k), 0);
  }
  if (resized || other || program.matrix_revision() != matrix_revision_) {
    rows_.Assign(program.constraint_matrix());
    columns_.AssignTransposeOf(rows_);
    matrix_revision_ = program.matrix_revision();
    analysed_ = false;
  }
  if (resized || other || program.hessian_revision() != hessian_revision_) {
    hessian_rows_.AssignSymmetric(program.hessian());
    hessian_revision_ = program.hessian_revision();
    analysed_ = false;
  }
  LoadBounds(program);
  if (!analysed_) Analyse();
  rho_ = settings_.primal_regularization;
  delta_ = settings_.equality_regularization;
  return !resized;
}

void BandedIpmQpSolver::LoadBounds(const Program& program) {
  // Each side is written at the next free place and kept by advancing sides_ when its bound is
  // finite: no branch on which bounds a constraint has (a branch per side mispredicted on the
  // body QP's mix of bounded and free variables). The per-side vectors have room for two sides
  // per constraint, so the writes past the kept ones stay inside them.
  sides_ = 0;
  equalities_.clear();
  bool consistent = true;
  int* constraint = side_constraint_.data();
  double* sign = side_sign_.data();
  double* bound = side_bound_.data();
  int sides = 0;
  const auto load = [&](int k, double lo, double up) {
    lo = NormalizeBound(lo);
    up = NormalizeBound(up);
    const bool finite_lo = std::isfinite(lo), finite_up = std::isfinite(up);
    lower_[k] = lo;
    upper_[k] = up;
    finite_lower_[k] = finite_lo ? lo : 0.0;
    finite_upper_[k] = finite_up ? up : 0.0;
    bounded_[k] = finite_lo || finite_up ? 1.0 : 0.0;
    consistent = consistent && !(lo > up);
    const bool equality = lo == up;
    if (equality) equalities_.push_back(k);  // within the reserved capacity
    constraint[sides] = k;
    sign[sides] = 1.0;
    bound[sides] = lo;
    sides += finite_lo && !equality ? 1 : 0;
    constraint[sides] = k;
    sign[sides] = -1.0;
    bound[sides] = up;
    sides += finite_up && !equality ? 1 : 0;
  };
  const Eigen::VectorXd &row_lower = program.row_lower(), &row_upper = program.row_upper();
  const Eigen::VectorXd &variable_lower = program.variable_lower(), &variable_upper = program.variable_upper();
  for (int k = 0; k < m_; ++k) load(k, row_lower[k], row_upper[k]);
  for (int j = 0; j < n_; ++j) load(m_ + j, variable_lower[j], variable_upper[j]);
  sides_ = sides;
  bounds_consistent_ = consistent;
}

void BandedIpmQpSolver::Analyse() {
  // The pattern of H + A'A: H's off-diagonal nonzeros, and each row's nonzeros pairwise.
  ordering_.Reset(n_);
  double pairs = 0.0;
  for (int k = 0; k < m_; ++k) {
    const double count = rows_.RowEnd(k) - rows_.RowBegin(k);
    pairs += 0.5 * count * (count - 1);
  }
  if (pairs > kDenseEdgeFraction * static_cast<double>(n_) * static_cast<double>(n_)) {
    ordering_.KeepDense();
  } else {
    ordering_.Reserve(static_cast<std::size_t>(pairs) + static_cast<std::size_t>(hessian_rows_.nonzeros()));
    for (int i = 0; i < n_; ++i) {
      for (int e = hessian_rows_.RowBegin(i); e < hessian_rows_.RowEnd(i); ++e) {
        if (hessian_rows_.ColumnAt(e) < i) ordering_.AddEdge(i, hessian_rows_.ColumnAt(e));
      }
    }
    for (int k = 0; k < m_; ++k) {
      for (int e = rows_.RowBegin(k); e < rows_.RowEnd(k); ++e) {
        for (int f = rows_.RowBegin(k); f < e; ++f) ordering_.AddEdge(rows_.ColumnAt(e), rows_.ColumnAt(f));
      }
    }
    ordering_.Compute();
  }
  factor_.Resize(n_, ordering_.bandwidth());
  // Where Assemble() adds: H's lower triangle once (its values do not change within a solve),
  // the diagonal, and each row's pairs of nonzeros with their products.
  const auto at = [this](int i) { return ordering_.position(i); };
  factor_.SetZero();
  for (int i = 0; i < n_; ++i) {
    const int pi = at(i);
    for (int e = hessian_rows_.RowBegin(i); e < hessian_rows_.RowEnd(i); ++e) {
      const int pj = at(hessian_rows_.ColumnAt(e));
      if (pi >= pj) factor_.Add(pi, pj, hessian_rows_.ValueAt(e));
    }
  }
  const std::size_t band_size = static_cast<std::size_t>(n_) * static_cast<std::size_t>(factor_.bandwidth() + 1);
  h_band_.assign(factor_.data(), factor_.data() + band_size);
  diagonal_slot_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) {
    diagonal_slot_[static_cast<std::size_t>(i)] = static_cast<int>(factor_.Offset(at(i), at(i)));
  }
  pair_slot_.clear();
  pair_product_.clear();
  const std::size_t slots = static_cast<std::size_t>(pairs) + static_cast<std::size_t>(rows_.nonzeros());
  pair_slot_.reserve(slots);  // a row's pairs in the lower triangle, its diagonal products included
  pair_product_.reserve(slots);
  pair_end_.resize(static_cast<std::size_t>(m_));
  for (int k = 0; k < m_; ++k) {
    for (int e = rows_.RowBegin(k); e < rows_.RowEnd(k); ++e) {
      const int pe = at(rows_.ColumnAt(e));
      for (int f = rows_.RowBegin(k); f < rows_.RowEnd(k); ++f) {
        const int pf = at(rows_.ColumnAt(f));
        if (pe < pf) continue;
        pair_slot_.push_back(static_cast<int>(factor_.Offset(pe, pf)));
        pair_product_.push_back(rows_.ValueAt(e) * rows_.ValueAt(f));
      }
    }
    pair_end_[static_cast<std::size_t>(k)] = static_cast<int>(pair_slot_.size());
  }
  analysed_ = true;
}

void BandedIpmQpSolver::ComputeValues(const Eigen::VectorXd& x, Eigen::VectorXd* values) const {
  rows_.Multiply(x, values);
  values->tail(n_) = x;
}

void BandedIpmQpSolver::ComputeResiduals() {
  // Each per-side pass fuses its gather or scatter with its arithmetic (local pointers, so the
  // compiler need not reload members after every store).
  const int n = sides_;
  const int* constraint = side_constraint_.data();
  const double* sign = side_sign_.data();
  const double* s = s_.data();
  const double* l = l_.data();
  y_ = w_;
  double* y = y_.data();
  for (int j = 0; j < n; ++j) y[constraint[j]] -= sign[j] * l[j];
  measures_ = Measure(x_, y_, &v_, &hx_, &r_dual_);
  const double* v = v_.data();
  const double* bound = side_bound_.data();
  double* r = r_.data();
  for (int j = 0; j < n; ++j) r[j] = sign[j] * (v[constraint[j]] - bound[j]) - s[j];
  mu_ = n > 0 ? s_.head(n).dot(l_.head(n)) / n : 0.0;
}

void BandedIpmQpSolver::Residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& y, Eigen::VectorXd* values,
                                  Eigen::VectorXd* hx, Eigen::VectorXd* r_dual) const {
  ComputeValues(x, values);
  hessian_rows_.Multiply(x, hx);
  const Eigen::VectorXd& g = program_->linear_cost();
  columns_.Multiply(y, r_dual);  // A'y
  for (int j = 0; j < n_; ++j) (*r_dual)[j] = (*hx)[j] + g[j] + (*r_dual)[j] + y[m_ + j];
}

BandedIpmQpSolver::Measures BandedIpmQpSolver::Measure(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                                       Eigen::VectorXd* values, Eigen::VectorXd* hx,
                                                       Eigen::VectorXd* r_dual) const {
  Residuals(x, y, values, hx, r_dual);
  const Eigen::VectorXd& g = program_->linear_cost();
  Measures out;
  // qpbenchmark's support term (GapSupportTerm) and violation over every constraint, without a
  // branch per constraint: an infinite side's finite_ stand-in is 0 and its violation -inf.
  const auto v = values->array();
  const auto yk = y.array();
  const double support = (yk.max(0.0) * finite_upper_.array() + yk.min(0.0) * finite_lower_.array()).sum();
  out.primal = std::max({0.0, (lower_.array() - v).maxCoeff(), (v - upper_.array()).maxCoeff()});
  out.primal_scale = (v.abs() * bounded_.array()).maxCoeff();
  out.combination = (*r_dual - *hx - g).lpNorm<Eigen::Infinity>();
  out.dual = r_dual->lpNorm<Eigen::Infinity>();
  const double xhx = x.dot(*hx), gx = g.dot(x);
  out.gap = std::abs(xhx + gx + support);
  out.support = support;
  out.dual_scale = std::max({hx->lpNorm<Eigen::Infinity>(), g.lpNorm<Eigen::Infinity>(), out.combination});
  out.gap_scale = std::max({std::abs(xhx), std::abs(gx), std::abs(support)});
  return out;
}

bool BandedIpmQpSolver::Converged(const Measures& e) const {
  const double tol = settings_.tolerance, rel = settings_.relative_tolerance;
  return e.primal <= tol + rel * e.primal_scale && e.dual <= tol + rel * e.dual_scale &&
         e.gap <= tol + rel * e.gap_scale;
}

bool BandedIpmQpSolver::NearOptimum(const Measures& e) const {
  return e.gap <= settings_.tolerance + kEarlyPolishGap * e.gap_scale;
}

bool BandedIpmQpSolver::ConvergedAbsolute(const Measures& e) const {
  const double tol = settings_.tolerance;
  return e.primal <= tol && e.dual <= tol && e.gap <= tol;
}

bool BandedIpmQpSolver::ClearlyWrongSet() const {
  // After the polish's first step its point is the regularised system's solution, within about
  // delta of the exact one, which the further steps only refine: a multiplier of the wrong sign
  // or an inactive constraint violated by kWrongSetMargin of their size will still be there.
  const double y_margin = kWrongSetMargin * (1.0 + yp_.lpNorm<Eigen::Infinity>());
  for (int k = 0; k < n_ + m_; ++k) {
    const ActiveSide side = active_[static_cast<std::size_t>(k)];
    const double v = vp_[k] + dv_[k];  // the values at the new point
    const double v_margin = kWrongSetMargin * (1.0 + std::abs(v));
    if (side == 0 && (v < lower_[k] - v_margin || v > upper_[k] + v_margin)) return true;
    if (side != 0 && lower_[k] != upper_[k] && side * yp_[k] < -y_margin) return true;
  }
  return false;
}

bool BandedIpmQpSolver::IsInfeasible() const {
  // Growing multipliers y with A'y + z ~ 0 and a negative support value prove that no x meets
  // the constraints (Farkas): y'(A x) <= support(y) < 0 = (A'y + z)'x would be needed.
  const double y_norm = y_.lpNorm<Eigen::Infinity>();
  const double gradient = (hx_ + program_->linear_cost()).lpNorm<Eigen::Infinity>();
  if (!(y_norm > kLargeDualRatio * (1.0 + gradient))) return false;
  return measures_.combination <= kCombinationTol * y_norm && measures_.support < -kCertificateTol * y_norm;
}

bool BandedIpmQpSolver::IsUnbounded() const {
  // x running off: its direction d = x / |x| is a ray of unboundedness when H d ~ 0, g'd < 0
  // and every constraint's value moves only away from its finite sides along it.
  const double norm = x_.lpNorm<Eigen::Infinity>();
  if (!(norm > kLargePrimal)) return false;
  const double tol = kCertificateTol * norm;
  if (hx_.lpNorm<Eigen::Infinity>() > tol || !(program_->linear_cost().dot(x_) < -tol)) return false;
  for (int k = 0; k < n_ + m_; ++k) {
    if (std::isfinite(lower_[k]) && v_[k] - lower_[k] < -tol) return false;
    if (std::isfinite(upper_[k]) && v_[k] - upper_[k] > tol) return false;
  }
  return true;
}

void BandedIpmQpSolver::Factorize() {
  inverse_s_.head(sides_) = s_.head(sides_).cwiseInverse();  // the two directions divide by s too
  inverse_l_.head(sides_) = l_.head(sides_).cwiseInverse();  // and MaxStep() by s and l
  d_.setZero();
  const int* constraint = side_constraint_.data();
  const double* l = l_.data();
  const double* inv_s = inverse_s_.data();
  double* d = d_.data();
  for (int j = 0; j < sides_; ++j) d[constraint[j]] += l[j] * inv_s[j];
  for (const int k : equalities_) d_[k] = 1.0 / delta_;
  Assemble();
  factor_.Factorize(kPivotTol);
}

void BandedIpmQpSolver::Assemble() {
  // The lower triangle of H + rho I + sum_k D_k a_k a_k', in the factor's order: H's part copied,
  // each row's products a_ke a_kf scaled by D_k into the places Analyse() looked up.
  double* band = factor_.data();
  std::copy(h_band_.begin(), h_band_.end(), band);
  for (int i = 0; i < n_; ++i) band[diagonal_slot_[static_cast<std::size_t>(i)]] += rho_ + d_[m_ + i];
  int p = 0;
  for (int k = 0; k < m_; ++k) {
    const int end = pair_end_[static_cast<std::size_t>(k)];
    const double d = d_[k];
    if (d == 0.0) {
      p = end;
      continue;
    }
    for (; p < end; ++p) {
      band[pair_slot_[static_cast<std::size_t>(p)]] += d * pair_product_[static_cast<std::size_t>(p)];
    }
  }
}

void BandedIpmQpSolver::MultiplyReduced(const Eigen::VectorXd& v, Eigen::VectorXd* out) const {
  hessian_rows_.Multiply(v, out);
  for (int i = 0; i < n_; ++i) (*out)[i] += (rho_ + d_[m_ + i]) * v[i];
  for (int k = 0; k < m_; ++k) {
    if (d_[k] != 0.0) rows_.AddRow(k, d_[k] * rows_.RowDot(k, v), out);
  }
}

void BandedIpmQpSolver::SolveThroughFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd* solution) {
  for (int i = 0; i < n_; ++i) permuted_[ordering_.position(i)] = rhs[i];
  factor_.Solve(permuted_.data());
  for (int i = 0; i < n_; ++i) (*solution)[i] = permuted_[ordering_.position(i)];
}

void BandedIpmQpSolver::SolveReduced() {
  SolveThroughFactor(rhs_, &dx_);
  for (int step = 0; step < settings_.refinement_steps; ++step) {
    MultiplyReduced(dx_, &work_);
    work_ = rhs_ - work_;
    SolveThroughFactor(work_, &correction_);
    dx_ += correction_;
  }
}

void BandedIpmQpSolver::Direction() {
  // Per side: ds = sign dv + r and l ds + s dl = -rc give dl = -(rc + l ds) / s, which in the
  // stationarity row adds D dv + e with e = sign (rc + l r) / s. The gathers and scatters by
  // constraint fuse with the per-side arithmetic, the scatter into e with its terms
  // and MaxStep()'s rate in the same pass as the steps: one pass over the sides before the
  // solve, one after (local pointers, so stores do not make the compiler reload members).
  const int n = sides_;
  const int* constraint = side_constraint_.data();
  const double* sign = side_sign_.data();
  const double* l = l_.data();
  const double* inv_s = inverse_s_.data();
  const double* inv_l = inverse_l_.data();
  const double* rc = rc_.data();
  const double* r = r_.data();
  e_.setZero();
  double* e = e_.data();
  for (int j = 0; j < n; ++j) e[constraint[j]] += sign[j] * (rc[j] + l[j] * r[j]) * inv_s[j];
  for (const int k : equalities_) e_[k] = (v_[k] - lower_[k]) / delta_;
  columns_.Multiply(e_, &rhs_);  // A'e
  for (int i = 0; i < n_; ++i) rhs_[i] = -r_dual_[i] - rhs_[i] - e_[m_ + i];
  SolveReduced();
  ComputeValues(dx_, &dv_);
  const double* dv = dv_.data();
  double* ds = ds_.data();
  double* dl = dl_.data();
  double rate = 0.0;
  for (int j = 0; j < n; ++j) {
    const double dsj = sign[j] * dv[constraint[j]] + r[j];
    const double dlj = -(rc[j] + l[j] * dsj) * inv_s[j];
    ds[j] = dsj;
    dl[j] = dlj;
    rate = std::max(rate, std::max(-dsj * inv_s[j], -dlj * inv_l[j]));
  }
  step_rate_ = rate;
  dw_.setZero();
  for (const int k : equalities_) dw_[k] = (dv_[k] + v_[k] - lower_[k]) / delta_;
}

double BandedIpmQpSolver::MaxStep() const {
  // 1 / the fastest relative decrease of any slack or multiplier: products with their
  // reciprocals (Factorize()) instead of a division and a branch per side.
  // (Direction() takes the rate in its pass over the sides.)
  return step_rate_ > 0.0 ? 1.0 / step_rate_ : kInf;
}

double BandedIpmQpSolver::ComplementarityAfter(double alpha) const {
  if (sides_ == 0) return 0.0;
  const auto s = s_.head(sides_), l = l_.head(sides_), ds = ds_.head(sides_), dl = dl_.head(sides_);
  return (s + alpha * ds).dot(l + alpha * dl) / sides_;
}

void BandedIpmQpSolver::Step(double alpha) {
  // Tapia's indicator (El-Bakry, Tapia & Zhang 1994): an active side's slack falls faster than
  // its multiplier, an inactive side's multiplier faster than its slack. Unlike l > s it needs no
  // common unit for slacks (metres) and multipliers (newtons): on the body QP it names the
  // active set three iterations sooner, and the polish ends the solve there.
  // One pass over the sides through local pointers: the indicator and both updates together.
  double* s = s_.data();
  double* l = l_.data();
  const double* ds = ds_.data();
  const double* dl = dl_.data();
  int* leads = multiplier_leads_.data();
  for (int j = 0; j < sides_; ++j) {
    leads[j] = dl[j] * s[j] > ds[j] * l[j] ? 1 : 0;
    s[j] += alpha * ds[j];
    l[j] += alpha * dl[j];
  }
  x_ += alpha * dx_;
  w_ += alpha * dw_;
}

void BandedIpmQpSolver::StartingPoint() {
  // x minimises 0.5 x'Hx + g'x + 0.5 sum over finite sides (a_k'x - bound)^2 (+ the equalities
  // weighted 1 / delta): one factorisation, and x lands between two-sided bounds.
  d_.setZero();
  target_.setZero();
  for (int j = 0; j < sides_; ++j) {
    const int k = side_constraint_[static_cast<std::size_t>(j)];
    d_[k] += 1.0;
    target_[k] += side_bound_[j];
  }
  for (const int k : equalities_) {
    d_[k] = 1.0 / delta_;
    target_[k] = lower_[k] / delta_;
  }
  rhs_ = -program_->linear_cost();
  for (int k = 0; k < m_; ++k) {
    if (target_[k] != 0.0) rows_.AddRow(k, target_[k], &rhs_);
  }
  rhs_ += target_.tail(n_);
  Assemble();
  factor_.Factorize(kPivotTol);
  SolveReduced();
  x_ = dx_;
  ComputeValues(x_, &v_);
  w_.setZero();
  if (sides_ == 0) return;
  // The slacks as in Mehrotra's start (Nocedal & Wright, Numerical Optimization, section 14.3):
  // from x, shifted by 1.5 times the largest violation, then by half their mean. Shifts in the
  // data's own units keep narrow two-sided rows (a hip band 0.14 m wide) from starting with
  // slacks far wider than the band. The multipliers then put every side on the central path,
  // s_j l_j = mu0, with mu0 the mean slack times sqrt(1 + |g|_inf): multipliers grow with the
  // gradient they balance (the body QP's |g| is 4e4; unit multipliers cost it three more
  // iterations), and a side with a wide slack starts with a small multiplier.
  auto s = s_.head(sides_), l = l_.head(sides_);
  for (int j = 0; j < sides_; ++j) {
    s[j] = side_sign_[j] * (v_[side_constraint_[static_cast<std::size_t>(j)]] - side_bound_[j]);
  }
  s.array() += std::max(-1.5 * s.minCoeff(), 0.0);
  const double mean = s.mean();
  s.array() += mean > 0 ? 0.5 * mean : 1.0;
  const double mu0 = s.mean() * std::sqrt(1.0 + program_->linear_cost().lpNorm<Eigen::Infinity>());
  l = mu0 * s.cwiseInverse();
}

SolveStatus BandedIpmQpSolver::Iterate() {
  for (iterations_ = 0;; ++iterations_) {
    ComputeResiduals();
    if (!x_.allFinite() || !std::isfinite(mu_)) return SolveStatus::kNumericalError;
    const int changes = UpdateActiveSides();
    if (Converged(measures_)) return SolveStatus::kSolved;
    // Polish once the active set has settled (the same two iterations running), and again after
    // a failed polish only when mu has fallen much further. Each time mu has fallen by
    // kPolishProgress (from the start, then from the last such try) and the gap is small
    // (NearOptimum()), the polish is also tried on an active set that has not settled yet: the
    // set is often right an iteration before it is seen twice. Such a polish is kept only within
    // the absolute tolerance (one at a large program's round-off floor waits for a settled set,
    // from a closer iterate), stops early on a clearly wrong set, and its failure changes
    // nothing the iterations use, so they run as without it.
    if (iterations_ == 0) early_polish_mu_ = kPolishProgress * mu_;
    if (changes == 0 && iterations_ > 0 && mu_ <= next_polish_mu_) {
      if (Polish()) return SolveStatus::kSolved;
      next_polish_mu_ = kPolishProgress * mu_;
    } else if (iterations_ > 0 && mu_ <= early_polish_mu_ && NearOptimum(measures_)) {
      if (Polish(/*strict=*/true)) return SolveStatus::kSolved;
      early_polish_mu_ = kPolishProgress * mu_;
    }
    if (IsInfeasible()) return SolveStatus::kInfeasible;
    if (IsUnbounded()) return SolveStatus::kUnbounded;
    if (iterations_ >= settings_.max_iterations) return Polish() ? SolveStatus::kSolved : SolveStatus::kIterationLimit;
    if (has_deadline_ && std::chrono::steady_clock::now() > deadline_) return SolveStatus::kTimeLimit;
    Factorize();
    // Predictor: the affine-scaling direction (complementarity target 0).
    rc_.head(sides_) = s_.head(sides_).cwiseProduct(l_.head(sides_));
    Direction();
    const double mu_affine = ComplementarityAfter(std::min(1.0, MaxStep()));
    const double ratio = mu_ > 0 ? mu_affine / mu_ : 0.0;
    const double sigma = std::min(1.0, ratio * ratio * ratio);
    // Corrector: centring toward sigma mu plus the predictor's second-order term.
    rc_.head(sides_).array() += ds_.head(sides_).array() * dl_.head(sides_).array() - sigma * mu_;
    Direction();
    const double alpha = std::min(1.0, settings_.step_fraction * MaxStep());
    // A step that breaks down (at mu near round-off on a badly scaled program) may still leave
    // an iterate whose active set the polish can finish from.
    if (!std::isfinite(alpha) || !dx_.allFinite()) return Polish() ? SolveStatus::kSolved : SolveStatus::kNumericalError;
    Step(alpha);
  }
}

void BandedIpmQpSolver::FillResult(const Program& program, SolveStatus status, SolveResult* result) const {
  result->status = status;
  result->x = x_;
  result->row_duals = y_.head(m_);
  result->bound_duals = y_.tail(n_);
  result->objective = 0.5 * x_.dot(hx_) + program.linear_cost().dot(x_) + program.constant();
  std::copy(active_.begin(), active_.begin() + m_, result->active_set.rows.begin());
  std::copy(active_.begin() + m_, active_.end(), result->active_set.bounds.begin());
  result->info.iterations = iterations_;
  result->info.primal_residual = measures_.primal;
  result->info.dual_residual = measures_.dual;
}

int BandedIpmQpSolver::UpdateActiveSides() {
  // Active where the last step shrank the slack relatively more than the multiplier (Step()),
  // before any step where the multiplier exceeds the slack; an equality always, on its lower
  // side as SolveResult's convention has it.
  // Through local pointers: a store of an int8 side may alias any member the loop would reload.
  active_.swap(previous_active_);
  ActiveSide* active = active_.data();
  std::fill(active, active + active_.size(), ActiveSide{0});
  const int* constraint = side_constraint_.data();
  const double* sign = side_sign_.data();
  if (iterations_ > 0) {
    const int* leads = multiplier_leads_.data();
    for (int j = 0; j < sides_; ++j) {
      if (leads[j] != 0) active[constraint[j]] = sign[j] > 0 ? -1 : 1;
    }
  } else {
    const double* s = s_.data();
    const double* l = l_.data();
    for (int j = 0; j < sides_; ++j) {
      if (l[j] > s[j]) active[constraint[j]] = sign[j] > 0 ? -1 : 1;
    }
  }
  for (const int k : equalities_) active[k] = -1;
  const ActiveSide* previous = previous_active_.data();
  int changes = 0;
  for (std::size_t k = 0; k < active_.size(); ++k) changes += active[k] != previous[k] ? 1 : 0;
  return changes;
}

bool BandedIpmQpSolver::Polish(bool strict) {
  // The equality-constrained QP on the active set the iterate points at, solved by iterative
  // refinement of its regularised KKT system: H dx + A'dy = r1, A dx - delta dy = r2, with r1
  // and r2 the unregularised residuals, so the refinement converges to the exact KKT point.
  // Kept only when its duals have the right signs, the inactive constraints hold and
  // qpbenchmark's measures come out within tolerance: then the solve ends with an active-set
  // solver's accuracy instead of the interior point's last digits.
  for (int k = 0; k < n_ + m_; ++k) {
    const ActiveSide side = active_[static_cast<std::size_t>(k)];
    d_[k] = side != 0 ? 1.0 / delta_ : 0.0;
    yp_[k] = side != 0 ? y_[k] : 0.0;
    target_[k] = side > 0 ? upper_[k] : lower_[k];
  }
  Assemble();
  factor_.Factorize(kPivotTol);
  xp_ = x_;
  for (int step = 0; step < kPolishSteps; ++step) {
    Residuals(xp_, yp_, &vp_, &hxp_, &rdp_);
    rhs_ = -rdp_;
    for (int k = 0; k < n_ + m_; ++k) {
      if (active_[static_cast<std::size_t>(k)] != 0) AddNormal(k, (target_[k] - vp_[k]) / delta_, &rhs_);
    }
    SolveReduced();
    xp_ += dx_;
    ComputeValues(dx_, &dv_);
    for (int k = 0; k < n_ + m_; ++k) {
      if (active_[static_cast<std::size_t>(k)] != 0) yp_[k] += (dv_[k] - (target_[k] - vp_[k])) / delta_;
    }
    if (strict && step == 0 && ClearlyWrongSet()) return false;
  }
  polish_measures_ = Measure(xp_, yp_, &vp_, &hxp_, &rdp_);
  for (int k = 0; k < n_ + m_; ++k) {
    const bool equality = lower_[k] == upper_[k];  // its multiplier has no sign
    if (!equality && active_[static_cast<std::size_t>(k)] * yp_[k] < -settings_.tolerance) return false;
  }
  if (!Converged(polish_measures_) || (strict && !ConvergedAbsolute(polish_measures_))) return false;
  x_ = xp_;
  y_ = yp_;
  v_ = vp_;
  hx_ = hxp_;
  r_dual_ = rdp_;
  measures_ = polish_measures_;
  return true;
}

}  // namespace stairplan::optim
