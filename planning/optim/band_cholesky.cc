// Band Cholesky, column by column (right-looking): each finished column updates the b columns
// after it, over their stored entries only.
#include "planning/optim/band_cholesky.h"

#include <algorithm>
#include <cmath>

namespace stairplan::optim {
namespace {

// A replaced pivot: its square root divides the column, so its entries and the solution's
// component there come out about 1e-32 of what they would be.
constexpr double kHugePivot = 1e64;

}  // namespace

void BandCholesky::Resize(int n, int bandwidth) {
  n_ = n;
  b_ = std::max(0, std::min(bandwidth, n - 1));
  const std::size_t need = static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1);
  if (band_.size() < need) band_.resize(need);
  if (inverse_pivot_.size() < static_cast<std::size_t>(n_)) inverse_pivot_.resize(static_cast<std::size_t>(n_));
}

void BandCholesky::SetZero() {
  std::fill_n(band_.begin(), static_cast<std::ptrdiff_t>(n_) * (b_ + 1), 0.0);
}

int BandCholesky::Factorize(double pivot_tol) {
  double largest = 0.0;
  for (int j = 0; j < n_; ++j) largest = std::max(largest, band_[Index(j, j)]);
  const double floor = pivot_tol * std::max(largest, 1e-300);
  int replaced = 0;
  for (int j = 0; j < n_; ++j) {
    double* col = &band_[Index(j, j)];
    const int len = std::min(b_, n_ - 1 - j);
    if (!(col[0] > floor)) {  // also NaN
      col[0] = kHugePivot;
      ++replaced;
    }
    const double pivot = std::sqrt(col[0]);
    col[0] = pivot;
    const double inv = 1.0 / pivot;
    inverse_pivot_[static_cast<std::size_t>(j)] = inv;
    for (int i = 1; i <= len; ++i) col[i] *= inv;
    for (int k = 1; k <= len; ++k) {
      const double v = col[k];
      if (v == 0.0) continue;
      double* target = &band_[Index(j + k, j + k)];  // column j + k, from its diagonal
      for (int i = k; i <= len; ++i) target[i - k] -= col[i] * v;
    }
  }
  return replaced;
}

void BandCholesky::Solve(double* rhs) const {
  for (int j = 0; j < n_; ++j) {  // L y = rhs
    const double* col = &band_[Index(j, j)];
    const int len = std::min(b_, n_ - 1 - j);
    const double y = rhs[j] * inverse_pivot_[static_cast<std::size_t>(j)];
    rhs[j] = y;
    for (int i = 1; i <= len; ++i) rhs[j + i] -= col[i] * y;
  }
  for (int j = n_ - 1; j >= 0; --j) {  // L' x = y
    const double* col = &band_[Index(j, j)];
    const int len = std::min(b_, n_ - 1 - j);
    double sum = rhs[j];
    for (int i = 1; i <= len; ++i) sum -= col[i] * rhs[j + i];
    rhs[j] = sum * inverse_pivot_[static_cast<std::size_t>(j)];
  }
}

}  // namespace stairplan::optim
