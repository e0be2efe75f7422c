#include "planning/optim/sparse_rows.h"

#include <algorithm>

namespace stairplan::optim {

void SparseRows::Resize(int m, int n) {
  m_ = m;
  n_ = n;
  start_.assign(static_cast<std::size_t>(m) + 1, 0);
  end_.assign(static_cast<std::size_t>(m), 0);
  column_.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(n), 0);
  value_.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(n), 0.0);
}

namespace {

// Slots a row of `nonzeros` gets when the copy is built (never more than the n columns, so the
// m x n storage always suffices).
int RowCapacity(int nonzeros, int n) { return std::min(n, 2 * nonzeros + 4); }

}  // namespace

void SparseRows::Assign(const Eigen::MatrixXd& a) {
  // Row by row over a column-major matrix: strided reads, but only when a row outgrows its slots.
  ++builds_;
  int e = 0;
  for (int k = 0; k < m_; ++k) {
    start_[static_cast<std::size_t>(k)] = e;
    e = FillRow(a, k);
    const int used = e - start_[static_cast<std::size_t>(k)];
    e = start_[static_cast<std::size_t>(k)] + RowCapacity(used, n_);
  }
  start_[static_cast<std::size_t>(m_)] = e;
}

int SparseRows::FillRow(const Eigen::MatrixXd& a, int k) {
  int e = start_[static_cast<std::size_t>(k)];
  for (int i = 0; i < n_; ++i) {
    const double v = a(k, i);
    if (v == 0.0) continue;
    column_[static_cast<std::size_t>(e)] = i;
    value_[static_cast<std::size_t>(e)] = v;
    ++e;
  }
  end_[static_cast<std::size_t>(k)] = e;
  return e;
}

void SparseRows::UpdateRow(const Eigen::MatrixXd& a, int k) {
  int nonzeros = 0;
  for (int i = 0; i < n_; ++i) nonzeros += a(k, i) != 0.0 ? 1 : 0;
  if (nonzeros > start_[static_cast<std::size_t>(k) + 1] - start_[static_cast<std::size_t>(k)]) {
    Assign(a);
    return;
  }
  FillRow(a, k);
}

void SparseRows::Multiply(const Eigen::VectorXd& x, Eigen::VectorXd* y) const {
  for (int k = 0; k < m_; ++k) (*y)[k] = RowDot(k, x);
}

void SparseRows::AddTransposeMultiply(const Eigen::VectorXd& u, Eigen::VectorXd* y) const {
  for (int k = 0; k < m_; ++k) {
    const double uk = u[k];
    if (uk == 0.0) continue;
    for (int e = start_[static_cast<std::size_t>(k)]; e < end_[static_cast<std::size_t>(k)]; ++e) {
      (*y)[column_[static_cast<std::size_t>(e)]] += value_[static_cast<std::size_t>(e)] * uk;
    }
  }
}

void SparseRows::TransposedTimesRow(const Eigen::MatrixXd& j, int k, double sigma, Eigen::VectorXd* d) const {
  d->setZero();
  for (int e = start_[static_cast<std::size_t>(k)]; e < end_[static_cast<std::size_t>(k)]; ++e) {
    const double a = sigma * value_[static_cast<std::size_t>(e)];
    if (a != 0.0) d->noalias() += a * j.row(column_[static_cast<std::size_t>(e)]).transpose();
  }
}

}  // namespace stairplan::optim
