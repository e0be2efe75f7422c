#include "planning/optim/sparse_rows.h"

namespace stairplan::optim {

void SparseRows::Resize(int m, int n) {
  m_ = m;
  n_ = n;
  start_.assign(static_cast<std::size_t>(m) + 1, 0);
  column_.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(n), 0);
  value_.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(n), 0.0);
}

void SparseRows::Assign(const Eigen::MatrixXd& a) {
  // Row by row over a column-major matrix: strided reads, but only when the matrix changes.
  int e = 0;
  for (int k = 0; k < m_; ++k) {
    start_[static_cast<std::size_t>(k)] = e;
    for (int i = 0; i < n_; ++i) {
      const double v = a(k, i);
      if (v == 0.0) continue;
      column_[static_cast<std::size_t>(e)] = i;
      value_[static_cast<std::size_t>(e)] = v;
      ++e;
    }
  }
  start_[static_cast<std::size_t>(m_)] = e;
}

void SparseRows::UpdateRow(const Eigen::MatrixXd& a, int k) {
  const int begin = start_[static_cast<std::size_t>(k)], end = start_[static_cast<std::size_t>(k) + 1];
  // Every nonzero of the new row must have a slot; slots of entries that became zero keep a zero.
  int e = begin;
  for (int i = 0; i < n_; ++i) {
    const double v = a(k, i);
    while (e < end && column_[static_cast<std::size_t>(e)] < i) value_[static_cast<std::size_t>(e++)] = 0.0;
    if (e < end && column_[static_cast<std::size_t>(e)] == i) {
      value_[static_cast<std::size_t>(e++)] = v;
    } else if (v != 0.0) {
      Assign(a);
      return;
    }
  }
  for (; e < end; ++e) value_[static_cast<std::size_t>(e)] = 0.0;
}

void SparseRows::Multiply(const Eigen::VectorXd& x, Eigen::VectorXd* y) const {
  for (int k = 0; k < m_; ++k) (*y)[k] = RowDot(k, x);
}

void SparseRows::AddTransposeMultiply(const Eigen::VectorXd& u, Eigen::VectorXd* y) const {
  for (int k = 0; k < m_; ++k) {
    const double uk = u[k];
    if (uk == 0.0) continue;
    for (int e = start_[static_cast<std::size_t>(k)]; e < start_[static_cast<std::size_t>(k) + 1]; ++e) {
      (*y)[column_[static_cast<std::size_t>(e)]] += value_[static_cast<std::size_t>(e)] * uk;
    }
  }
}

void SparseRows::TransposedTimesRow(const Eigen::MatrixXd& j, int k, double sigma, Eigen::VectorXd* d) const {
  d->setZero();
  for (int e = start_[static_cast<std::size_t>(k)]; e < start_[static_cast<std::size_t>(k) + 1]; ++e) {
    const double a = sigma * value_[static_cast<std::size_t>(e)];
    if (a != 0.0) d->noalias() += a * j.row(column_[static_cast<std::size_t>(e)]).transpose();
  }
}

}  // namespace stairplan::optim
