// Band L D L' (Cholesky without its square roots), column by column (right-looking): each
// finished column updates the b columns after it, over their stored entries only. The
// knot-structured programs it is for have narrow bands (4 on the body QP), where loops of b
// iterations cost more in their bookkeeping than in their arithmetic: bands up to kFixedBands
// wide run through copies of the kernels with b known at compile time (unrolled), wider ones
// through the same kernels with b at run time.
#include "stairplan/optim/band_cholesky.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace stairplan::optim {
namespace {

// A replaced pivot divides its column, so its entries and the solution's component there come
// out about 1e-64 of what they would be.
constexpr double kHugePivot = 1e64;
// Half-bandwidths with their own compiled kernels.
constexpr int kFixedBands = 8;

// The kernels over band storage (column j's entries j..j+b at band[j (b + 1)], the diagonal
// first). kB > 0: the half-bandwidth known at compile time; 0: `runtime_b`. Each calls its
// column step with the column's length as a compile-time constant where it is the full band
// (all but the last b columns), so that its loops unroll.
template <int kB, typename Step>
void ForEachColumn(int n, int b, Step step) {
  for (int j = 0; j < n; ++j) {
    if (kB > 0 && j + kB < n) {
      step(j, std::integral_constant<int, kB>{});
    } else {
      step(j, std::min(b, n - 1 - j));
    }
  }
}

template <int kB>
int FactorizeBand(double* band, double* inverse_pivot, int n, int runtime_b, double floor) {
  const int b = kB > 0 ? kB : runtime_b;
  int replaced = 0;
  ForEachColumn<kB>(n, b, [&](int j, auto len) {
    double* col = band + static_cast<std::ptrdiff_t>(j) * (b + 1);
    if (!(col[0] > floor)) {  // also NaN
      col[0] = kHugePivot;
      ++replaced;
    }
    const double inv = 1.0 / col[0];
    inverse_pivot[j] = inv;
    // The next column's pivot waits on this one's through a division, a product and an update
    // (a square root more in L L'): the chain that sets a narrow band's speed.
    for (int k = 1; k <= len; ++k) {
      const double lk = col[k] * inv;  // col still holds d_j l_ij: a_ik -= a_ij a_kj / d_j
      double* target = col + static_cast<std::ptrdiff_t>(k) * (b + 1);  // column j + k, from its diagonal
      for (int i = k; i <= len; ++i) target[i - k] -= col[i] * lk;
    }
    for (int i = 1; i <= len; ++i) col[i] *= inv;
  });
  return replaced;
}

// L y = rhs, then D L' x = y; with kB > 0 the entries still to come ride in registers (a store
// followed by a load of the same entry costs more than the multiply-add between them).
template <int kB>
void SolveBand(const double* band, const double* inverse_pivot, int n, int runtime_b, double* rhs) {
  const int b = kB > 0 ? kB : runtime_b;
  int j = 0;
  if constexpr (kB > 0) {
    if (n > kB) {
      double w[kB];  // rhs[j .. j + kB - 1], partly eliminated
      for (int i = 0; i < kB; ++i) w[i] = rhs[i];
      for (; j + kB < n; ++j) {
        const double* col = band + static_cast<std::ptrdiff_t>(j) * (kB + 1);
        const double y = w[0];
        rhs[j] = y;
        for (int i = 1; i < kB; ++i) w[i - 1] = w[i] - col[i] * y;
        w[kB - 1] = rhs[j + kB] - col[kB] * y;
      }
      for (int i = 0; i < kB; ++i) rhs[j + i] = w[i];
    }
  }
  for (; j < n; ++j) {
    const double* col = band + static_cast<std::ptrdiff_t>(j) * (b + 1);
    const int len = std::min(b, n - 1 - j);
    const double y = rhs[j];
    for (int i = 1; i <= len; ++i) rhs[j + i] -= col[i] * y;
  }
  // Backward: the last b rows with their shorter columns, then the rest with full ones.
  const int tail = kB > 0 ? std::max(0, n - kB) : 0;
  for (j = n - 1; j >= tail; --j) {
    const double* col = band + static_cast<std::ptrdiff_t>(j) * (b + 1);
    const int len = std::min(b, n - 1 - j);
    double sum = rhs[j] * inverse_pivot[j];
    for (int i = len; i >= 1; --i) sum -= col[i] * rhs[j + i];
    rhs[j] = sum;
  }
  if constexpr (kB > 0) {
    if (tail > 0) {
      double v[kB];  // x[j + 1 .. j + kB]
      for (int i = 0; i < kB; ++i) v[i] = rhs[tail + i];
      for (j = tail - 1; j >= 0; --j) {
        const double* col = band + static_cast<std::ptrdiff_t>(j) * (kB + 1);
        double sum = rhs[j] * inverse_pivot[j];
        for (int i = kB; i >= 1; --i) sum -= col[i] * v[i - 1];  // x[j + 1], the newest, last
        for (int i = kB - 1; i >= 1; --i) v[i] = v[i - 1];
        v[0] = sum;
        rhs[j] = sum;
      }
    }
  }
}

// Calls kernel<b> for b up to kFixedBands, kernel<0> beyond.
template <template <int> class Kernel, typename... Args>
auto Dispatch(int b, Args... args) {
  switch (b) {
    case 1: return Kernel<1>::Run(args...);
    case 2: return Kernel<2>::Run(args...);
    case 3: return Kernel<3>::Run(args...);
    case 4: return Kernel<4>::Run(args...);
    case 5: return Kernel<5>::Run(args...);
    case 6: return Kernel<6>::Run(args...);
    case 7: return Kernel<7>::Run(args...);
    case kFixedBands: return Kernel<kFixedBands>::Run(args...);
    default: return Kernel<0>::Run(args...);
  }
}

template <int kB>
struct FactorizeKernel {
  static int Run(double* band, double* inverse_pivot, int n, int b, double floor) {
    return FactorizeBand<kB>(band, inverse_pivot, n, b, floor);
  }
};
template <int kB>
struct SolveKernel {
  static void Run(const double* band, const double* inverse_pivot, int n, int b, double* rhs) {
    SolveBand<kB>(band, inverse_pivot, n, b, rhs);
  }
};

}  // namespace

void BandCholesky::Resize(int n, int bandwidth) {
  n_ = n;
  b_ = std::max(0, std::min(bandwidth, n - 1));
  const std::size_t need = static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1);
  if (band_.size() < need) band_.resize(need);
  if (inverse_pivot_.size() < static_cast<std::size_t>(n_)) inverse_pivot_.resize(static_cast<std::size_t>(n_));
}

void BandCholesky::SetZero() { std::fill_n(band_.begin(), static_cast<std::ptrdiff_t>(n_) * (b_ + 1), 0.0); }

int BandCholesky::Factorize(double pivot_tol) {
  double largest = 0.0;
  for (int j = 0; j < n_; ++j) largest = std::max(largest, band_[Index(j, j)]);
  const double floor = pivot_tol * std::max(largest, 1e-300);
  return Dispatch<FactorizeKernel>(b_, band_.data(), inverse_pivot_.data(), n_, b_, floor);
}

void BandCholesky::Solve(double* rhs) const {
  Dispatch<SolveKernel>(b_, band_.data(), inverse_pivot_.data(), n_, b_, rhs);
}

}  // namespace stairplan::optim
