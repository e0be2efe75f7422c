#include "stairplan/optim/sparse_rows.h"

#include <algorithm>
#include <array>
#include <cmath>

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
  // Rows before k hold at most n slots each, so row k's n columns always fit the m x n storage.
  ++builds_;
  int e = 0;
  for (int k = 0; k < m_; ++k) {
    start_[static_cast<std::size_t>(k)] = e;
    FillRow(a, k, e + n_);
    e += RowCapacity(end_[static_cast<std::size_t>(k)] - e, n_);
  }
  start_[static_cast<std::size_t>(m_)] = e;
}

void SparseRows::AssignPacked(const Eigen::MatrixXd& a) {
  // One pass over the column-major matrix collects each column's nonzeros (in scratch storage);
  // a pass over the nonzeros then sorts them into rows.
  ++builds_;
  m_ = static_cast<int>(a.rows());
  n_ = static_cast<int>(a.cols());
  std::size_t count = 0;
  scratch_column_end_.resize(static_cast<std::size_t>(n_));
  for (int j = 0; j < n_; ++j) {
    // Room for the whole column, so that the loop below writes every entry and only advances
    // past nonzeros: no branch on the pattern (mispredicted at every nonzero).
    const std::size_t room = count + static_cast<std::size_t>(m_);
    if (scratch_row_.size() < room) scratch_row_.resize(2 * room);
    if (scratch_value_.size() < room) scratch_value_.resize(2 * room);
    const double* col = a.data() + static_cast<std::ptrdiff_t>(j) * m_;
    const auto take = [&](int k) {
      scratch_row_[count] = k;
      scratch_value_[count] = col[k];
      count += col[k] != 0.0 ? 1 : 0;
    };
    int k = 0;
    for (; k + 4 <= m_; k += 4) {  // runs of zeros (most of a banded matrix) skipped four at a time
      if (col[k] == 0.0 && col[k + 1] == 0.0 && col[k + 2] == 0.0 && col[k + 3] == 0.0) continue;
      take(k), take(k + 1), take(k + 2), take(k + 3);
    }
    for (; k < m_; ++k) take(k);
    scratch_column_end_[static_cast<std::size_t>(j)] = static_cast<int>(count);
  }
  if (column_.size() < count) column_.resize(count);
  if (value_.size() < count) value_.resize(count);
  start_.assign(static_cast<std::size_t>(m_) + 1, 0);
  for (std::size_t e = 0; e < count; ++e) ++start_[static_cast<std::size_t>(scratch_row_[e]) + 1];
  for (int k = 0; k < m_; ++k) start_[static_cast<std::size_t>(k) + 1] += start_[static_cast<std::size_t>(k)];
  end_.assign(start_.begin(), start_.end() - 1);  // each row's cursor, ending at its end
  std::size_t e = 0;
  for (int j = 0; j < n_; ++j) {  // columns ascending, so each row's columns come out ascending
    for (; e < static_cast<std::size_t>(scratch_column_end_[static_cast<std::size_t>(j)]); ++e) {
      const std::size_t slot = static_cast<std::size_t>(end_[static_cast<std::size_t>(scratch_row_[e])]++);
      column_[slot] = j;
      value_[slot] = scratch_value_[e];
    }
  }
}

bool SparseRows::FillRow(const Eigen::MatrixXd& a, int k, int limit) {
  int e = start_[static_cast<std::size_t>(k)];
  for (int i = 0; i < n_; ++i) {
    const double v = a(k, i);
    if (v == 0.0) continue;
    if (e == limit) return false;
    column_[static_cast<std::size_t>(e)] = i;
    value_[static_cast<std::size_t>(e)] = v;
    ++e;
  }
  end_[static_cast<std::size_t>(k)] = e;
  return true;
}

void SparseRows::UpdateRow(const Eigen::MatrixXd& a, int k) {
  if (!FillRow(a, k, start_[static_cast<std::size_t>(k) + 1])) Assign(a);
}

bool SparseRows::UpdateRowAt(const Eigen::MatrixXd& a, int k, const int* columns, int count) {
  // The union of the two ascending lists, read from `a`, into a small buffer first: the row's
  // slots are overwritten from their start.
  constexpr int kMerged = 32;
  const std::size_t row = static_cast<std::size_t>(k);
  const int first = start_[row], present = end_[row] - first;
  if (present + count > kMerged) return false;
  std::array<int, kMerged> merged_column;
  std::array<double, kMerged> merged_value;
  int merged = 0, i = first, j = 0;
  while (i < end_[row] || j < count) {
    int column;
    if (j == count || (i < end_[row] && column_[static_cast<std::size_t>(i)] < columns[j])) {
      column = column_[static_cast<std::size_t>(i++)];
    } else {
      column = columns[j++];
      if (i < end_[row] && column_[static_cast<std::size_t>(i)] == column) ++i;
    }
    const double v = a(k, column);
    if (v == 0.0) continue;
    merged_column[static_cast<std::size_t>(merged)] = column;
    merged_value[static_cast<std::size_t>(merged)] = v;
    ++merged;
  }
  if (first + merged > start_[row + 1]) {
    Assign(a);  // outgrew its slots
    return true;
  }
  for (int e = 0; e < merged; ++e) {
    column_[static_cast<std::size_t>(first + e)] = merged_column[static_cast<std::size_t>(e)];
    value_[static_cast<std::size_t>(first + e)] = merged_value[static_cast<std::size_t>(e)];
  }
  end_[row] = first + merged;
  return true;
}

double SparseRows::RowNorm(int k) const {
  double sum = 0.0;
  for (int e = start_[static_cast<std::size_t>(k)]; e < end_[static_cast<std::size_t>(k)]; ++e) {
    sum += value_[static_cast<std::size_t>(e)] * value_[static_cast<std::size_t>(e)];
  }
  return std::sqrt(sum);
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
