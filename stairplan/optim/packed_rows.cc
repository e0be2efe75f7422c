#include "stairplan/optim/packed_rows.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace stairplan::optim {
namespace {

// The bits of x without its sign: zero exactly for +0 and -0 (a NaN counts as a nonzero).
inline std::uint64_t MagnitudeBits(const double* x) {
  std::uint64_t bits;
  std::memcpy(&bits, x, sizeof bits);
  return bits << 1;
}

constexpr int kChunk = 8;

// Rows padded to at most this many entries, and only while padding at most doubles the entries
// (plus one per row).
constexpr int kMaxPaddedWidth = 8;

template <int kWidth>
void MultiplyPadded(const int* column, const double* value, int rows, const double* x, double* y) {
  for (int k = 0; k < rows; ++k) {
    const int* c = column + static_cast<std::ptrdiff_t>(k) * kWidth;
    const double* v = value + static_cast<std::ptrdiff_t>(k) * kWidth;
    double sum = 0.0;
    for (int t = 0; t < kWidth; ++t) sum += v[t] * x[c[t]];
    y[k] = sum;
  }
}

}  // namespace

void PackedRows::Multiply(const Eigen::VectorXd& x, Eigen::VectorXd* y) const {
  const int* c = padded_column_.data();
  const double* v = padded_value_.data();
  double* out = y->data();
  switch (padded_width_) {
    case 1: return MultiplyPadded<1>(c, v, m_, x.data(), out);
    case 2: return MultiplyPadded<2>(c, v, m_, x.data(), out);
    case 3: return MultiplyPadded<3>(c, v, m_, x.data(), out);
    case 4: return MultiplyPadded<4>(c, v, m_, x.data(), out);
    case 5: return MultiplyPadded<5>(c, v, m_, x.data(), out);
    case 6: return MultiplyPadded<6>(c, v, m_, x.data(), out);
    case 7: return MultiplyPadded<7>(c, v, m_, x.data(), out);
    case 8: return MultiplyPadded<8>(c, v, m_, x.data(), out);
    default:
      for (int k = 0; k < m_; ++k) out[k] = RowDot(k, x);
  }
}

void PackedRows::Pad() {
  const auto size = [](int v) { return static_cast<std::size_t>(v); };
  int width = 0;
  for (int k = 0; k < m_; ++k) width = std::max(width, RowEnd(k) - RowBegin(k));
  const long padded = static_cast<long>(width) * m_;
  padded_width_ = 0;
  if (width == 0 || width > kMaxPaddedWidth || padded > 2L * nonzeros() + m_) return;
  if (padded_column_.size() < size(static_cast<int>(padded))) padded_column_.resize(size(static_cast<int>(padded)));
  if (padded_value_.size() < size(static_cast<int>(padded))) padded_value_.resize(size(static_cast<int>(padded)));
  for (int k = 0; k < m_; ++k) {
    const int begin = RowBegin(k), end = RowEnd(k);
    const int pad_column = begin < end ? ColumnAt(begin) : 0;
    const std::size_t row = size(k) * size(width);
    for (int t = 0; t < width; ++t) {
      const bool real = begin + t < end;
      padded_column_[row + size(t)] = real ? ColumnAt(begin + t) : pad_column;
      padded_value_[row + size(t)] = real ? ValueAt(begin + t) : 0.0;
    }
  }
  padded_width_ = width;
}

void PackedRows::Assign(const Eigen::MatrixXd& a) { Take(a, false); }

void PackedRows::AssignSymmetric(const Eigen::MatrixXd& a) { Take(a, true); }

void PackedRows::Take(const Eigen::MatrixXd& a, bool symmetric) {
  m_ = static_cast<int>(a.rows());
  n_ = static_cast<int>(a.cols());
  const auto size = [](int v) { return static_cast<std::size_t>(v); };
  scratch_column_end_.resize(size(n_));
  start_.assign(size(m_) + 1, 0);
  std::size_t count = 0;
  for (int j = 0; j < n_; ++j) {
    // Room for the whole column, so that every entry is written and only nonzeros advance the
    // count: no branch on the pattern inside a chunk.
    const std::size_t room = count + size(m_) + kChunk;
    if (scratch_row_.size() < room) scratch_row_.resize(2 * room);
    if (scratch_value_.size() < room) scratch_value_.resize(2 * room);
    const double* col = a.data() + static_cast<std::ptrdiff_t>(j) * m_;
    const int first = symmetric ? j : 0;
    const auto take = [&](int k) {
      scratch_row_[count] = k;
      scratch_value_[count] = col[k];
      count += MagnitudeBits(col + k) != 0 ? 1 : 0;
    };
    int k = first;
    for (; k + kChunk <= m_; k += kChunk) {
      std::uint64_t any = 0;
      for (int t = 0; t < kChunk; ++t) any |= MagnitudeBits(col + k + t);
      if (any == 0) continue;
      for (int t = 0; t < kChunk; ++t) take(k + t);
    }
    for (; k < m_; ++k) take(k);
    scratch_column_end_[size(j)] = static_cast<int>(count);
  }
  // Row counts (a symmetric matrix's entry below the diagonal also in its column's row), then
  // each row's slots filled column by column, so its columns come out ascending: row r's
  // entries from columns c <= r come from the columns before r's own, its mirrored ones (columns
  // above r) from column r, after its diagonal.
  for (std::size_t e = 0, j = 0; e < count; ++e) {
    while (e >= size(scratch_column_end_[j])) ++j;
    ++start_[size(scratch_row_[e]) + 1];
    if (symmetric && scratch_row_[e] != static_cast<int>(j)) ++start_[j + 1];
  }
  for (int k = 0; k < m_; ++k) start_[size(k) + 1] += start_[size(k)];
  const std::size_t total = size(start_[size(m_)]);
  if (column_.size() < total) column_.resize(total);
  if (value_.size() < total) value_.resize(total);
  cursor_.assign(start_.begin(), start_.end() - 1);
  std::size_t e = 0;
  for (int j = 0; j < n_; ++j) {
    const std::size_t begin = e, end = size(scratch_column_end_[size(j)]);
    for (; e < end; ++e) {
      const std::size_t slot = size(cursor_[size(scratch_row_[e])]++);
      column_[slot] = j;
      value_[slot] = scratch_value_[e];
    }
    if (!symmetric) continue;
    for (std::size_t f = begin; f < end; ++f) {  // (j, r) for the entries (r, j) below the diagonal
      if (scratch_row_[f] == j) continue;
      const std::size_t slot = size(cursor_[size(j)]++);
      column_[slot] = scratch_row_[f];
      value_[slot] = scratch_value_[f];
    }
  }
  Pad();
}

void PackedRows::AssignTransposeOf(const PackedRows& a) {
  const auto size = [](int v) { return static_cast<std::size_t>(v); };
  m_ = a.n_;
  n_ = a.m_;
  start_.assign(size(m_) + 1, 0);
  const std::size_t total = size(a.nonzeros());
  for (std::size_t e = 0; e < total; ++e) ++start_[size(a.column_[e]) + 1];
  for (int k = 0; k < m_; ++k) start_[size(k) + 1] += start_[size(k)];
  if (column_.size() < total) column_.resize(total);
  if (value_.size() < total) value_.resize(total);
  cursor_.assign(start_.begin(), start_.end() - 1);
  for (int k = 0; k < a.m_; ++k) {  // a's rows ascending: each new row's columns come out ascending
    for (int e = a.RowBegin(k); e < a.RowEnd(k); ++e) {
      const std::size_t slot = size(cursor_[size(a.ColumnAt(e))]++);
      column_[slot] = k;
      value_[slot] = a.ValueAt(e);
    }
  }
  Pad();
}

}  // namespace stairplan::optim
