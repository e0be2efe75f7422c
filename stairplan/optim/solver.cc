// The checked Solve(): validation, timing, result sizing.
#include "stairplan/optim/solver.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>


namespace stairplan::optim {
namespace {

void SizeResult(const Program& p, SolveResult* r) {
  const int n = p.num_variables(), m = p.num_rows();
  if (r->x.size() != n) r->x.resize(n);
  if (r->bound_duals.size() != n) r->bound_duals.resize(n);
  if (r->row_duals.size() != m) r->row_duals.resize(m);
  if (static_cast<int>(r->active_set.rows.size()) != m) r->active_set.rows.assign(m, 0);
  if (static_cast<int>(r->active_set.bounds.size()) != n) r->active_set.bounds.assign(n, 0);
}

// True when m holds a NaN. Every finite entry times 0 is 0 and a NaN or infinite one gives NaN, so
// a sum of those products is finite exactly when every entry is: sixteen independent sums without
// an early exit vectorise and keep both adders busy (about 5 times faster than Eigen's hasNaN(),
// whose all() stops at the first hit, on the body QP's 120 x 120 H and 194 x 120 A; eight sums
// were 3.5 times). Only when that sum is not finite is the matrix searched for a NaN itself: an
// infinite entry is not rejected here.
bool HasNaN(const Eigen::MatrixXd& m) {
  constexpr int kLanes = 16;
  const double* p = m.data();
  const Eigen::Index size = m.size();
  double lane[kLanes] = {};
  Eigen::Index i = 0;
  for (; i + kLanes <= size; i += kLanes) {
    for (int j = 0; j < kLanes; ++j) lane[j] += p[i + j] * 0.0;
  }
  double sum = 0.0;
  for (; i < size; ++i) sum += p[i] * 0.0;
  for (int j = 0; j < kLanes; ++j) sum += lane[j];
  return !std::isfinite(sum) && m.hasNaN();
}

}  // namespace

bool Solver::DataIsValid(const Program& p) {
  if (p.hessian_revision() != checked_hessian_revision_) {
    if (HasNaN(p.hessian())) return false;
    checked_hessian_revision_ = p.hessian_revision();
  }
  if (p.matrix_revision() != checked_matrix_revision_) {
    // Rows changed through SetConstraintCoefficients were checked there; whole-matrix changes
    // (MutableConstraintMatrix) are scanned here.
    if (p.whole_matrix_revision() != checked_whole_matrix_revision_ && HasNaN(p.constraint_matrix())) return false;
    checked_matrix_revision_ = p.matrix_revision();
    checked_whole_matrix_revision_ = p.whole_matrix_revision();
  }
  // A lower bound of +inf or an upper bound of -inf (1e400 in a file, or >= 1e20 normalised) is no
  // bound any value meets: without this check "x1 + x2 >= 1e400" was reported solved at x = 0.
  const auto impossible = [](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
    return lower.hasNaN() || upper.hasNaN() || (lower.array() == kInf).any() || (upper.array() == -kInf).any();
  };
  return !(p.linear_cost().hasNaN() || impossible(p.row_lower(), p.row_upper()) ||
           impossible(p.variable_lower(), p.variable_upper()) || p.initial_guess().hasNaN() ||
           std::isnan(p.constant()));
}

void Solver::Solve(const Program& program, SolveResult* result) {
  if (result == nullptr) throw std::invalid_argument("Solver::Solve: result must not be null");
  const auto start = std::chrono::steady_clock::now();
  SizeResult(program, result);
  result->info = SolveInfo{};
  if (program.num_variables() == 0 || !DataIsValid(program) || !Supports(program)) {
    result->status = SolveStatus::kInvalidInput;
    result->x.setZero();
    result->row_duals.setZero();
    result->bound_duals.setZero();
    result->objective = 0.0;
  } else {
    DoSolve(program, result);
  }
  result->info.solve_time_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

SolveResult Solver::Solve(const Program& program) {
  SolveResult result;
  Solve(program, &result);
  return result;
}

}  // namespace stairplan::optim
