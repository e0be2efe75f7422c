// The dual active-set (Goldfarb-Idnani) QP solver with warm starts and proximal regularisation.
//
// Notation: constraint k has normal n_k (row k of A, or e_i for a bound) and is active on one
// side; with sigma = +1 for a lower and -1 for an upper side it reads sigma n_k'x >= sigma b_k.
// With H = L L', the factorisation keeps J = L^{-T} Q and R such that J1' N = R for the active
// normals N (J1 = first q columns of J, J2 the rest), so
//   x = J1 R^{-T} b - J2 J2' g   and   u = R^{-1} (R^{-T} b + J1' g)
// are the minimiser on the active set and its multipliers (Hx + g = N u).
#include "stairplan/optim/active_set_qp_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stairplan::optim {
namespace {

// A constraint whose normal has a component below this (relative) in the free space J2 is
// linearly dependent on the active ones.
constexpr double kDependencyTol = 1e-10;
// A constraint that depends on the active ones, with no active multiplier to give way, is a
// certificate of infeasibility only when its violation exceeds this (relative to 1 + |bound|):
// below, the violation is the round-off of a degenerate vertex, where more constraints than
// variables meet (an elastic variable at its bound that rows pin there too).
constexpr double kDegenerateTol = 1e-6;
// Multipliers below -kDualTol * scale make a warm start dual infeasible.
constexpr double kDualTol = 1e-12;
// Treat H as singular when its smallest Cholesky pivot squared is below this times max |H_ii|.
constexpr double kSingularPivot = 1e-9;
// Iterates beyond this size mean the (regularised) problem runs off: unbounded.
constexpr double kUnboundedNorm = 1e15;
// Restarts (closed-form re-solves on the final active set) allowed to polish one solve.
constexpr int kMaxPolish = 5;
// The KKT residual below which no refinement step is taken: absolute, as the residuals users
// judge a solution by (qpbenchmark's) are.
constexpr double kRefineFloor = 1e-12;

// Where GCC or Clang targets x86-64, RotateColumns gets a second version in 256-bit vectors
// (AVX2), picked at load time on machines that have them: a quarter less time per rotation than
// in SSE2's 128 bits. AVX2 brings no fused multiply-add (that is FMA's own flag), so both
// versions round alike and the solver's results do not depend on the machine.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define STAIRPLAN_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define STAIRPLAN_AVX2_CLONE
#endif

// Givens rotation of two columns' entries: a <- c a + s b, b <- -s a + c b over `rows` of them.
// On the columns' contiguous storage: the hottest loop of every solve, and element access through
// Eigen's operator() is a call per element where it is not inlined (the sanitized -O1 build).
STAIRPLAN_AVX2_CLONE void RotateColumns(double* col_i, double* col_j, int rows, double c, double s) {
  for (int k = 0; k < rows; ++k) {
    const double a = col_i[k], b = col_j[k];
    col_i[k] = c * a + s * b;
    col_j[k] = -s * a + c * b;
  }
}

}  // namespace

void ActiveSetQpSettings::Validate() const {
  const auto fail = [](const std::string& field) {
    throw std::invalid_argument("ActiveSetQpSettings::" + field + " is out of range");
  };
  if (max_iterations <= 0) fail("max_iterations");
  if (max_outer_iterations <= 0) fail("max_outer_iterations");
  if (!(time_limit_s > 0)) fail("time_limit_s");
  if (!(feasibility_tol > 0 && feasibility_tol < 1)) fail("feasibility_tol");
  if (!(proximal_weight > 0)) fail("proximal_weight");
  if (!(proximal_tol > 0 && proximal_tol < 1)) fail("proximal_tol");
  if (!(proximal_objective_tol > 0 && proximal_objective_tol < 1)) fail("proximal_objective_tol");
  if (refinement_steps < 0) fail("refinement_steps");
}

void ActiveSetQpSolver::SetWarmStart(const ActiveSet& active_set) {
  warm_start_ = active_set;
  pending_warm_start_ = true;
}

void ActiveSetQpSolver::LoadBounds(const Program& program) {
  // The bounds do not change during a solve: one contiguous copy, and the lists of constraints
  // that can be violated (a finite side) and of equalities, so the scans skip free rows.
  lower_.head(m_) = program.row_lower();
  lower_.tail(n_) = program.variable_lower();
  upper_.head(m_) = program.row_upper();
  upper_.tail(n_) = program.variable_upper();
  bounded_.clear();
  equalities_.clear();
  for (int k = 0; k < m_ + n_; ++k) {
    if (std::isfinite(lower_[k]) || std::isfinite(upper_[k])) bounded_.push_back(k);
    if (IsEquality(k) && std::isfinite(lower_[k])) equalities_.push_back(k);
  }
}

double ActiveSetQpSolver::Value(int k) const { return k < m_ ? ax_[k] : x_[k - m_]; }

double ActiveSetQpSolver::RowValue(int k) const {
  return k < m_ ? rows_.RowDot(k, x_) : x_[k - m_];
}

bool ActiveSetQpSolver::OverLimits() {
  if (has_deadline_ && std::chrono::steady_clock::now() > deadline_) time_exceeded_ = true;
  return time_exceeded_ || iterations_ >= settings_.max_iterations;
}

void ActiveSetQpSolver::Prepare(const Program& program) {
  const int n = program.num_variables(), m = program.num_rows();
  const bool resized = n != n_ || m != m_;
  if (resized) {
    n_ = n;
    m_ = m;
    factorization_valid_ = false;
    hessian_revision_ = 0;
    J_.resize(n, n);
    R_.resize(n, n);
    J0_.resize(n, n);
    hessian_reg_.resize(n, n);
    j0_first_.assign(static_cast<std::size_t>(n), 0);
    column_begin_.assign(static_cast<std::size_t>(n), 0);
    column_end_.assign(static_cast<std::size_t>(n), n);
    active_.assign(n, -1);
    state_.assign(n + m, 0);
    set_aside_.assign(n + m, 0);
    u_.resize(n);
    for (Eigen::VectorXd* v : {&x_, &g_eff_, &x_prox_, &d_, &z_, &r_, &tmp_, &hx_, &dual_residual_,
                               &active_residual_, &saved_x_, &saved_u_}) {
      v->resize(n);
    }
    ax_.resize(m);
    row_norm_.resize(m);
    rows_.Resize(m, n);
    hessian_rows_.Resize(n, n);
    lower_.resize(n + m);
    upper_.resize(n + m);
    bounded_.reserve(static_cast<std::size_t>(n + m));
    readd_.reserve(static_cast<std::size_t>(n));
    equalities_.reserve(static_cast<std::size_t>(n + m));
    llt_ = Eigen::LLT<Eigen::MatrixXd>(n);
    q_ = 0;
    has_previous_ = false;
    if (!pending_warm_start_) {
      warm_start_.rows.assign(m, 0);
      warm_start_.bounds.assign(n, 0);
    }
  }
  if (resized || program.matrix_revision() != matrix_revision_) {
    if (!resized && program.whole_matrix_revision() == whole_matrix_revision_) {
      // Only some rows changed (SetConstraintCoefficients): the factorisation depends on the
      // active rows alone, so it stays valid once the changed active rows leave the active set
      // (the iteration adds them back with their new coefficients if they are still needed).
      // When so many active rows changed that dropping and re-adding them costs more rotations
      // than adding the whole active set from none, the factorisation is rebuilt from the active
      // set (the warm start).
      int changed_active = 0;
      // Rows written at a few known columns are read there, the others whole.
      const Eigen::MatrixXd& a = program.constraint_matrix();
      for (int k = 0; k < m; ++k) {
        if (program.row_revision(k) <= matrix_revision_) continue;
        if (state_[k] != 0) ++changed_active;
        const int* columns = nullptr;
        int count = 0;
        if (!program.WrittenColumns(k, matrix_revision_, &columns, &count) || !rows_.UpdateRowAt(a, k, columns, count)) {
          rows_.UpdateRow(a, k);
        }
        row_norm_[k] = std::max(rows_.RowNorm(k), 1e-300);
      }
      if (changed_active > 0 && (!factorization_valid_ || !ReaddCheaperThanRebuild(program))) {
        factorization_valid_ = false;
      } else if (changed_active > 0) {
        // The changed active rows leave the factorisation and, unless a given active set is to be
        // reached (pending_warm_start_), come straight back with their new coefficients: the
        // start is then the previous active set, as when nothing changed. Left out, they come back
        // only as the iteration finds them violated, after a restart whose multipliers, computed
        // without them, dropped their neighbours too (the body planner at 333 Hz, where every
        // cycle re-linearises every knot, took 2.4 times as long).
        readd_.clear();
        for (int position = q_ - 1; position >= 0; --position) {
          const int k = active_[position];
          if (k >= m || program.row_revision(k) <= matrix_revision_) continue;
          readd_.emplace_back(k, state_[k]);
          DropConstraint(position);
        }
        if (!pending_warm_start_) {
          for (const auto& [k, side] : readd_) {
            if (q_ == n_) break;
            ComputeStepVector(k, side < 0 ? 1.0 : -1.0);
            AddConstraint(k, side);
          }
        }
      }
    } else {
      whole_matrix_revision_ = program.whole_matrix_revision();
      factorization_valid_ = false;
      rows_.Assign(program.constraint_matrix());
      // Over the nonzeros, in the same order as over the dense row: the same sums, not a
      // strided pass over all of A.
      for (int k = 0; k < m; ++k) row_norm_[k] = std::max(rows_.RowNorm(k), 1e-300);
    }
    matrix_revision_ = program.matrix_revision();
  }
}

bool ActiveSetQpSolver::ReaddCheaperThanRebuild(const Program& program) const {
  // Both are counted in Givens rotations of J's columns, the work that dominates either: a drop
  // at position p rotates the q - 1 - p columns after it, an add at q the n - 1 - q free columns,
  // and a rebuild adds every active constraint from none. Drops go from the back, so each one
  // finds the later changed rows gone.
  long readd = 0;
  int dropped = 0;
  for (int position = q_ - 1; position >= 0; --position) {
    const int k = active_[position];
    if (k >= m_ || program.row_revision(k) <= matrix_revision_) continue;
    readd += (q_ - dropped) - 1 - position;
    ++dropped;
  }
  return readd + AddCost(q_ - dropped, dropped) <= AddCost(0, q_);
}

bool ActiveSetQpSolver::FactorizeHessian(const Program& program) {
  if (program.hessian_revision() == hessian_revision_) return true;
  factorization_valid_ = false;
  const Eigen::MatrixXd& H = program.hessian();
  hessian_rows_.Assign(H);
  const double scale = std::max(1.0, H.diagonal().cwiseAbs().maxCoeff());
  rho_ = 0.0;
  FindHessianBlocks(H);
  hessian_reg_ = H;
  llt_.compute(hessian_reg_);
  bool singular = llt_.info() != Eigen::Success;
  if (!singular) {
    const double min_pivot = llt_.matrixLLT().diagonal().minCoeff();
    singular = !(min_pivot * min_pivot > kSingularPivot * scale);
  }
  if (singular) {
    rho_ = settings_.proximal_weight * scale;
    hessian_reg_.diagonal().array() += rho_;
    llt_.compute(hessian_reg_);
    if (llt_.info() != Eigen::Success) return false;  // not positive semidefinite
  }
  // J0 = L^{-T}: the factorisation with no active constraint. Upper triangular: column j solves
  // L(s..j, s..j)' y = e_j from the first row s of j's diagonal block of H (L has H's blocks, and
  // the rows above s would come out exactly zero). Eigen's solve proceeds in panels counted from
  // the bottom, so rows s..j are computed by the same operations as in a solve from row 0: the
  // same bits, a fraction of the work when H has several blocks.
  J0_.setZero();
  const Eigen::MatrixXd& llt = llt_.matrixLLT();
  for (int j = 0; j < n_; ++j) {
    const int s = j0_first_[static_cast<std::size_t>(j)];
    J0_(j, j) = 1.0;
    llt.block(s, s, j + 1 - s, j + 1 - s).triangularView<Eigen::Lower>().transpose().solveInPlace(J0_.col(j).segment(s, j + 1 - s));
  }
  hessian_revision_ = program.hessian_revision();
  return true;
}

void ActiveSetQpSolver::FindHessianBlocks(const Eigen::MatrixXd& h) {
  // Row i's first nonzero in the lower triangle (column i's above the diagonal: contiguous), then
  // from the last row up the smallest of those over rows i..n-1: where that is i itself, no row
  // from i on couples to a variable before i, and a diagonal block starts at i.
  // j0_first_ holds that smallest first nonzero until the second pass turns it into the block's start.
  int lowest = n_;
  for (int i = n_ - 1; i >= 0; --i) {
    const double* column = h.col(i).data();
    int first = 0;
    while (first < i && column[first] == 0.0) ++first;
    lowest = std::min(lowest, first);
    j0_first_[static_cast<std::size_t>(i)] = lowest;
  }
  int start = 0;
  for (int i = 0; i < n_; ++i) {
    if (j0_first_[static_cast<std::size_t>(i)] == i) start = i;
    j0_first_[static_cast<std::size_t>(i)] = start;
  }
}

void ActiveSetQpSolver::StartCold() {
  J_ = J0_;
  for (int j = 0; j < n_; ++j) {
    column_begin_[static_cast<std::size_t>(j)] = j0_first_[static_cast<std::size_t>(j)];
    column_end_[static_cast<std::size_t>(j)] = j + 1;  // J0 is upper triangular
  }
  q_ = 0;
  std::fill(state_.begin(), state_.end(), 0);
  factorization_valid_ = true;
}

void ActiveSetQpSolver::RotateJ(int i, int j, double c, double s) {
  // Both columns are exactly zero outside their nonzero ranges, and stay so over the rows
  // outside the union: rotating there would only rewrite zeros.
  const std::size_t a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
  const int begin = std::min(column_begin_[a], column_begin_[b]);
  const int end = std::max(column_end_[a], column_end_[b]);
  column_begin_[a] = column_begin_[b] = begin;
  column_end_[a] = column_end_[b] = end;
  RotateColumns(J_.col(i).data() + begin, J_.col(j).data() + begin, end - begin, c, s);
}

void ActiveSetQpSolver::ComputeStepVector(int k, double sigma) {
  if (k < m_) {
    rows_.TransposedTimesRow(J_, k, sigma, &d_);
  } else {
    d_ = sigma * J_.row(k - m_).transpose();
  }
}

bool ActiveSetQpSolver::AddConstraint(int k, int side) {
  // d_ = J'(sigma n_k) must be current. Rotate d(q+1..n-1) into d(q) (and J alike).
  const double norm_d = d_.norm();
  for (int j = n_ - 1; j > q_; --j) {
    const double a = d_[j - 1], b = d_[j];
    if (b == 0.0) continue;
    const double h = std::sqrt(a * a + b * b);  // no overflow at our magnitudes; hypot is slow
    const double c = a / h, s = b / h;
    d_[j - 1] = h;
    d_[j] = 0.0;
    RotateJ(j - 1, j, c, s);
  }
  if (!(std::abs(d_[q_]) > kDependencyTol * norm_d)) return false;
  R_.col(q_).head(q_ + 1) = d_.head(q_ + 1);
  active_[q_] = k;
  state_[k] = static_cast<ActiveSide>(side);
  ++q_;
  return true;
}

void ActiveSetQpSolver::DropConstraint(int position) {
  state_[active_[position]] = 0;
  for (int j = position; j < q_ - 1; ++j) {
    R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
    active_[j] = active_[j + 1];
    u_[j] = u_[j + 1];
  }
  --q_;
  // R is upper Hessenberg from `position` on: rotate rows (j, j+1) and columns of J alike.
  for (int j = position; j < q_; ++j) {
    const double a = R_(j, j), b = R_(j + 1, j);
    if (b == 0.0) continue;
    const double h = std::sqrt(a * a + b * b);  // no overflow at our magnitudes; hypot is slow
    const double c = a / h, s = b / h;
    R_(j, j) = h;
    R_(j + 1, j) = 0.0;
    for (int col = j + 1; col < q_; ++col) {
      const double ra = R_(j, col), rb = R_(j + 1, col);
      R_(j, col) = c * ra + s * rb;
      R_(j + 1, col) = -s * ra + c * rb;
    }
    RotateJ(j, j + 1, c, s);
    const double ta = tmp_[j], tb = tmp_[j + 1];  // keeps tmp_ = J' g where Restart relies on it
    tmp_[j] = c * ta + s * tb;
    tmp_[j + 1] = -s * ta + c * tb;
  }
}

void ActiveSetQpSolver::StartFromActiveSet(const ActiveSet& set) {
  StartCold();
  AddEqualities();
  AddActive(set);
}

void ActiveSetQpSolver::MoveToActiveSet(const ActiveSet& set) {
  // From the back: a drop rotates the factorisation from its position on.
  for (int j = q_ - 1; j >= 0; --j) {
    const int k = active_[j];
    if (IsEquality(k)) continue;
    if (SideIn(set, k) != state_[k]) DropConstraint(j);
  }
  AddActive(set);
}

long ActiveSetQpSolver::AddCost(int q, int adds) const {
  long cost = 0;
  for (int i = 0; i < adds && q + i < n_; ++i) cost += n_ - 1 - (q + i);
  return cost;
}

ActiveSide ActiveSetQpSolver::SideIn(const ActiveSet& set, int k) const {
  if (k < m_) return k < static_cast<int>(set.rows.size()) ? set.rows[static_cast<std::size_t>(k)] : 0;
  const int i = k - m_;
  return i < static_cast<int>(set.bounds.size()) ? set.bounds[static_cast<std::size_t>(i)] : 0;
}

void ActiveSetQpSolver::AddActive(const ActiveSet& set) {
  for (int k = 0; k < m_ + n_; ++k) {
    const ActiveSide side = SideIn(set, k);
    if (side == 0 || state_[k] != 0 || q_ == n_) continue;
    if (!std::isfinite(side < 0 ? Lower(k) : Upper(k))) continue;
    ComputeStepVector(k, side < 0 ? 1.0 : -1.0);
    AddConstraint(k, side);
  }
}

void ActiveSetQpSolver::AddEqualities() {
  for (const int k : equalities_) {
    if (state_[k] != 0) continue;
    if (q_ == n_) break;
    ComputeStepVector(k, 1.0);
    AddConstraint(k, -1);  // dependent rows are skipped here and checked for violation later
  }
}

void ActiveSetQpSolver::ComputeMultipliers() {
  // b (in r_), then a = R^{-T} b (in r_) and u = R^{-1} (a + J1' g), with J' g in tmp_.
  for (int j = 0; j < q_; ++j) {
    const int k = active_[j];
    r_[j] = state_[k] < 0 ? Lower(k) : -Upper(k);
  }
  const int q = q_;
  if (q == 0) return;
  R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().transpose().solveInPlace(r_.head(q));
  u_.head(q) = r_.head(q) + tmp_.head(q);
  R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().solveInPlace(u_.head(q));
}

void ActiveSetQpSolver::ComputePrimal() {
  // x = J1 a - J2 J2' g (a in r_ and J' g in tmp_ from ComputeMultipliers).
  const int q = q_;
  x_.noalias() = -J_.rightCols(n_ - q) * tmp_.tail(n_ - q);
  if (q > 0) x_.noalias() += J_.leftCols(q) * r_.head(q);
}

int ActiveSetQpSolver::Restart() {
  int drops = 0;
  // Active constraints whose bound disappeared (made infinite by an update) cannot stay.
  for (int j = q_ - 1; j >= 0; --j) {
    const int k = active_[j];
    if (!std::isfinite(state_[k] < 0 ? Lower(k) : Upper(k))) {
      DropConstraint(j);
      ++drops;
    }
  }
  AddEqualities();
  // J' g once: a drop rotates columns of J, and DropConstraint rotates tmp_ alike, so only the
  // O(q^2) multipliers are recomputed per drop, and x once at the end.
  tmp_.noalias() = J_.transpose() * g_eff_;
  for (;;) {
    ComputeMultipliers();
    int worst = -1;
    double most_negative = 0.0;
    for (int j = 0; j < q_; ++j) {
      if (IsEquality(active_[j])) continue;
      const double scale = 1.0 + std::abs(u_[j]);
      if (u_[j] < -kDualTol * scale && u_[j] < most_negative) {
        most_negative = u_[j];
        worst = j;
      }
    }
    if (worst < 0) break;
    DropConstraint(worst);
    ++drops;
  }
  ComputePrimal();
  rows_.Multiply(x_, &ax_);
  return drops;
}

SolveStatus ActiveSetQpSolver::Iterate() {
  const double tol = settings_.feasibility_tol;
  std::fill(set_aside_.begin(), set_aside_.end(), 0);
  for (;;) {
    if (OverLimits()) return time_exceeded_ ? SolveStatus::kTimeLimit : SolveStatus::kIterationLimit;
    // Step 1: the most violated constraint (violation scaled by the normal's length).
    int p = -1, side = 0;
    double worst = 0.0;
    for (const int k : bounded_) {
      if (state_[k] != 0 || set_aside_[k] != 0) continue;
      const double v = Value(k), lo = Lower(k), hi = Upper(k);
      const double norm = k < m_ ? row_norm_[k] : 1.0;
      if (v < lo && lo - v > tol * (1.0 + std::abs(lo))) {
        const double score = (lo - v) / norm;
        if (score > worst) { worst = score; p = k; side = -1; }
      } else if (v > hi && v - hi > tol * (1.0 + std::abs(hi))) {
        const double score = (v - hi) / norm;
        if (score > worst) { worst = score; p = k; side = 1; }
      }
    }
    if (p < 0) return SolveStatus::kSolved;
    const double sigma = side < 0 ? 1.0 : -1.0;
    const double bound = side < 0 ? Lower(p) : Upper(p);
    double u_p = 0.0;
    // Step 2: move primal and dual until p is satisfied (full step) or a multiplier hits zero.
    for (;;) {
      if (OverLimits()) return time_exceeded_ ? SolveStatus::kTimeLimit : SolveStatus::kIterationLimit;
      ComputeStepVector(p, sigma);
      const int q = q_;
      // z = J2 d2 over the columns d reaches: J's free columns often still hold the untouched
      // block structure of L^{-T} (e.g. variables no active row involves), where d is exactly 0.
      int reach = n_;
      while (reach > q && d_[reach - 1] == 0.0) --reach;
      int from = q;
      while (from < reach && d_[from] == 0.0) ++from;
      if (reach > from) {
        z_.noalias() = J_.middleCols(from, reach - from) * d_.segment(from, reach - from);
      } else {
        z_.setZero();
      }
      const double free_norm2 = d_.tail(n_ - q).squaredNorm();
      if (q > 0) {
        r_.head(q) = d_.head(q);
        R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().solveInPlace(r_.head(q));
      }
      double t1 = kInf;
      int drop = -1;
      for (int j = 0; j < q; ++j) {
        if (r_[j] > 0.0 && !IsEquality(active_[j])) {
          const double ratio = u_[j] / r_[j];
          if (ratio < t1) { t1 = ratio; drop = j; }
        }
      }
      const double slack = sigma * (RowValue(p) - bound);  // negative while violated
      if (!d_.allFinite()) return SolveStatus::kNumericalError;  // not a certificate of anything
      const bool dependent = !(free_norm2 > kDependencyTol * kDependencyTol * d_.squaredNorm());
      const double t2 = dependent ? kInf : std::max(0.0, -slack / free_norm2);
      if (t1 == kInf && t2 == kInf) {
        if (-slack > kDegenerateTol * (1.0 + std::abs(bound))) return SolveStatus::kInfeasible;
        // Round-off at a degenerate vertex: p counts as met. The partial steps taken for it
        // are undone by re-solving the active set in closed form (dropping what that leaves
        // with a negative multiplier).
        set_aside_[static_cast<std::size_t>(p)] = 1;
        iterations_ += Restart();
        break;
      }
      ++iterations_;
      const double t = std::min(t1, t2);
      if (!dependent) x_.noalias() += t * z_;
      if (q > 0) u_.head(q) -= t * r_.head(q);
      u_p += t;
      if (t2 <= t1) {
        if (!AddConstraint(p, side)) return SolveStatus::kNumericalError;
        u_[q_ - 1] = u_p;
        break;
      }
      DropConstraint(drop);
    }
    rows_.Multiply(x_, &ax_);
    if (!(x_.lpNorm<Eigen::Infinity>() < kUnboundedNorm)) return SolveStatus::kUnbounded;
  }
}

void ActiveSetQpSolver::DoSolve(const Program& program, SolveResult* result) {
  program_ = &program;
  iterations_ = 0;
  time_exceeded_ = false;
  has_deadline_ = std::isfinite(settings_.time_limit_s);
  if (has_deadline_) {
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                    std::chrono::duration<double>(settings_.time_limit_s));
  }
  const double previous_rho = rho_;
  Prepare(program);
  LoadBounds(program);
  if (!FactorizeHessian(program)) {
    x_ = program.initial_guess();
    return FillResult(program, SolveStatus::kInvalidInput, result);  // H is not positive semidefinite
  }
  if (rho_ != previous_rho) factorization_valid_ = false;
  if (OverLimits()) {
    x_ = program.initial_guess();
    return FillResult(program, SolveStatus::kTimeLimit, result);
  }
  const bool regularized = rho_ > 0.0;
  // The proximal centre starts at the previous solution when warm, else at the initial guess.
  // Hot: the kept factorisation is valid (H and A unchanged); a given active set is reached from
  // it by the drops and adds in which the two differ, a handful where rebuilding costs one add per
  // active constraint. Warm: H or A changed, so the factorisation is rebuilt from the previous (or
  // a given) active set. Cold: from nothing.
  const bool hot = settings_.warm_start && factorization_valid_;
  bool started_warm = hot;
  if (hot) {
    x_prox_ = x_;
    if (pending_warm_start_) {
      MoveToActiveSet(warm_start_);
      pending_warm_start_ = false;
    }
  } else {
    x_prox_ = program.initial_guess();
    if (!pending_warm_start_ && settings_.warm_start && has_previous_) {
      warm_start_.rows.resize(m_);  // no-op unless a caller's warm start had other sizes
      warm_start_.bounds.resize(n_);
      for (int k = 0; k < m_; ++k) warm_start_.rows[k] = state_[k];
      for (int i = 0; i < n_; ++i) warm_start_.bounds[i] = state_[m_ + i];
      pending_warm_start_ = true;
    }
    if (pending_warm_start_) {
      started_warm = true;
      StartFromActiveSet(warm_start_);
      pending_warm_start_ = false;
    } else {
      StartCold();
    }
  }
  has_previous_ = true;
  int outer = 0;
  SolveStatus status = Run(regularized, &outer);
  result->info.cold_restarts = 0;
  // A warm or hot start is only a shortcut: the working set it brings may be one the current
  // bounds make useless (far from the optimum, or close to dependent after many updates), and
  // an Infeasible or NumericalError from it is not a certificate. Only the cold start, where
  // the dual iterates grow from the unconstrained minimum, decides those outcomes.
  if (started_warm && (status == SolveStatus::kInfeasible || status == SolveStatus::kNumericalError ||
                       status == SolveStatus::kUnbounded || !x_.allFinite()) &&
      !OverLimits()) {
    x_prox_ = program.initial_guess();
    StartCold();
    int cold_outer = 0;
    status = Run(regularized, &cold_outer);
    outer += cold_outer;
    result->info.cold_restarts = 1;
  }
  result->info.outer_iterations = outer;
  FillResult(program, status, result);
}

SolveStatus ActiveSetQpSolver::Run(bool regularized, int* outer_iterations) {
  const Program& program = *program_;
  const Eigen::VectorXd& g = program.linear_cost();
  SolveStatus status = SolveStatus::kIterationLimit;
  int outer = 0;
  for (; outer < (regularized ? settings_.max_outer_iterations : 1); ++outer) {
    g_eff_ = g;
    if (regularized) g_eff_.noalias() -= rho_ * x_prox_;
    status = SolveStatus::kIterationLimit;
    for (int polish = 0; polish < kMaxPolish; ++polish) {
      iterations_ += Restart();
      const int before = iterations_;
      status = Iterate();
      if (status != SolveStatus::kSolved) break;
      // Nothing changed since Restart: x and u are already its closed form, and Iterate found
      // nothing violated, so the polish below would repeat the same computation.
      if (iterations_ == before) break;
      // Polish: recompute x and u in closed form on the final active set; done when that point
      // needs no change (no negative multiplier, nothing violated).
      const int q_before = q_;
      if (Restart() == 0 && q_ == q_before && MeetsBounds(settings_.feasibility_tol, /*inactive_only=*/true)) break;
    }
    if (status != SolveStatus::kSolved || !regularized) break;
    const double step = (x_ - x_prox_).lpNorm<Eigen::Infinity>();
    if (IsUnboundedRay()) {
      status = SolveStatus::kUnbounded;
      break;
    }
    x_prox_ = x_;
    // x solves the original problem up to a dual residual of rho * step (the proximal term's
    // gradient); stop when that residual can change the objective by a negligible amount, or when
    // the iterates stand still.
    const double x_norm = x_.lpNorm<Eigen::Infinity>();
    hessian_rows_.Multiply(x_, &hx_);
    const double objective = 0.5 * x_.dot(hx_) + g.dot(x_) + program.constant();
    if (step <= settings_.proximal_tol * (1.0 + x_norm) ||
        rho_ * step * (1.0 + x_norm) <= settings_.proximal_objective_tol * (1.0 + std::abs(objective))) {
      ++outer;
      break;
    }
    if (OverLimits()) {
      status = time_exceeded_ ? SolveStatus::kTimeLimit : SolveStatus::kIterationLimit;
      break;
    }
    if (outer + 1 == settings_.max_outer_iterations) status = SolveStatus::kIterationLimit;
  }
  if (status == SolveStatus::kSolved && settings_.refinement_steps > 0) Refine();
  // Solved means feasible. On a nearly dependent active set the multipliers can be wrong enough
  // that a re-solve in closed form drops scores of constraints and lands far outside bounds the
  // iteration had met, and the polish may run out on such a point: an error, not an optimum.
  if (status == SolveStatus::kSolved && !(x_.allFinite() && MeetsBounds(kDegenerateTol, /*inactive_only=*/false))) {
    status = SolveStatus::kNumericalError;
  }
  *outer_iterations = outer;
  return status;
}

bool ActiveSetQpSolver::MeetsBounds(double relative_tol, bool inactive_only) const {
  for (const int k : bounded_) {
    if (inactive_only && state_[k] != 0) continue;
    const double v = Value(k), lo = Lower(k), hi = Upper(k);
    if (lo - v > relative_tol * (1.0 + std::abs(lo)) || v - hi > relative_tol * (1.0 + std::abs(hi))) return false;
  }
  return true;
}

double ActiveSetQpSolver::ActiveResiduals() {
  // Hx + g = N u and N'x = b on the active set, N's columns sigma n_k, b_k = sigma bound_k.
  hessian_rows_.Multiply(x_, &dual_residual_);
  dual_residual_ += program_->linear_cost();
  double worst = 0.0;
  for (int j = 0; j < q_; ++j) {
    const int k = active_[j];
    const double sigma = state_[k] < 0 ? 1.0 : -1.0;
    if (k < m_) {
      rows_.AddRow(k, -sigma * u_[j], &dual_residual_);
    } else {
      dual_residual_[k - m_] -= sigma * u_[j];
    }
    active_residual_[j] = sigma * (RowValue(k) - (state_[k] < 0 ? Lower(k) : Upper(k)));
    worst = std::max(worst, std::abs(active_residual_[j]));
  }
  return std::max(worst, dual_residual_.lpNorm<Eigen::Infinity>());
}

void ActiveSetQpSolver::Refine() {
  // The Givens updates leave rounding in J and R that grows with the active-set changes, and the
  // closed form inherits it; a correction (dx, du) solving the KKT system with the residuals on
  // the right, through the same J and R, removes most of it. With a proximal term the
  // factorisation is of H + rho I: the correction is then an approximate one, kept only while it
  // lowers the residuals.
  double error = ActiveResiduals();
  for (int step = 0; step < settings_.refinement_steps && error > kRefineFloor; ++step) {
    saved_x_ = x_;
    saved_u_.head(q_) = u_.head(q_);
    const int q = q_;
    // H dx - N du = -r_d, N' dx = -r_p: the closed form with g = r_d and b = -r_p.
    tmp_.noalias() = J_.transpose() * dual_residual_;
    r_.head(q) = -active_residual_.head(q);
    if (q > 0) {
      R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().transpose().solveInPlace(r_.head(q));
      d_.head(q) = r_.head(q) + tmp_.head(q);
      R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().solveInPlace(d_.head(q));
      u_.head(q) += d_.head(q);
      x_.noalias() += J_.leftCols(q) * r_.head(q);
    }
    x_.noalias() -= J_.rightCols(n_ - q) * tmp_.tail(n_ - q);
    const double refined = ActiveResiduals();
    if (!(refined < error)) {
      x_ = saved_x_;
      u_.head(q) = saved_u_.head(q);
      break;
    }
    error = refined;
  }
  rows_.Multiply(x_, &ax_);
}

bool ActiveSetQpSolver::IsUnboundedRay() {
  // d = x_{k+1} - x_k certifies unboundedness when H d = 0, g'd < 0 and d moves away from (or
  // along) every finite bound: then x + s d stays feasible and the objective falls without end.
  d_ = x_ - x_prox_;
  const double norm = d_.lpNorm<Eigen::Infinity>();
  if (!(norm > 1e-6 * (1.0 + x_.lpNorm<Eigen::Infinity>()))) return false;
  d_ /= norm;
  const Eigen::VectorXd& g = program_->linear_cost();
  if (!(g.dot(d_) < -1e-9 * (1.0 + g.lpNorm<Eigen::Infinity>()))) return false;
  hessian_rows_.Multiply(d_, &hx_);
  if (hx_.lpNorm<Eigen::Infinity>() > 1e-9 * (1.0 + program_->hessian().diagonal().cwiseAbs().maxCoeff())) return false;
  for (int k = 0; k < m_ + n_; ++k) {
    const double rate = k < m_ ? rows_.RowDot(k, d_) : d_[k - m_];
    const double tol = 1e-9 * (k < m_ ? row_norm_[k] : 1.0);
    if (std::isfinite(Lower(k)) && rate < -tol) return false;
    if (std::isfinite(Upper(k)) && rate > tol) return false;
  }
  return true;
}

void ActiveSetQpSolver::FillResult(const Program& program, SolveStatus status, SolveResult* result) {
  result->status = status;
  result->x = x_;
  result->row_duals.setZero();
  result->bound_duals.setZero();
  std::fill(result->active_set.rows.begin(), result->active_set.rows.end(), 0);
  std::fill(result->active_set.bounds.begin(), result->active_set.bounds.end(), 0);
  if (factorization_valid_) {
    for (int j = 0; j < q_; ++j) {
      const int k = active_[j];
      const double sigma = state_[k] < 0 ? 1.0 : -1.0;
      const double dual = -sigma * u_[j];
      if (k < m_) {
        result->row_duals[k] = dual;
        result->active_set.rows[k] = state_[k];
      } else {
        result->bound_duals[k - m_] = dual;
        result->active_set.bounds[k - m_] = state_[k];
      }
    }
  }
  hessian_rows_.Multiply(x_, &hx_);
  result->objective = 0.5 * x_.dot(hx_) + program.linear_cost().dot(x_) + program.constant();
  // Residuals of the original (unregularised) problem.
  double primal = 0.0;
  rows_.Multiply(x_, &ax_);
  for (const int k : bounded_) {
    const double v = Value(k), lo = Lower(k), hi = Upper(k);
    if (lo > -kInf) primal = std::max(primal, lo - v);
    if (hi < kInf) primal = std::max(primal, v - hi);
  }
  hx_ += program.linear_cost();
  hx_ += result->bound_duals;
  rows_.AddTransposeMultiply(result->row_duals, &hx_);
  result->info.primal_residual = primal;
  result->info.dual_residual = hx_.lpNorm<Eigen::Infinity>();
  result->info.iterations = iterations_;
}

}  // namespace stairplan::optim
