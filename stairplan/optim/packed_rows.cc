#include "stairplan/optim/packed_rows.h"

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

}  // namespace

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
}

}  // namespace stairplan::optim
