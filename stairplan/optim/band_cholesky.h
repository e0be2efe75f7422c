// BandCholesky: the Cholesky factorisation of a symmetric positive definite matrix whose
// nonzeros lie within `bandwidth` of the diagonal, in band storage, as L D L' with unit L
// (Golub & Van Loan, Matrix Computations, section 4.3: band Cholesky and band L D L'). Without
// the square roots each column's pivot waits on the one before through one division fewer.
//
// Why: the interior-point QP solver's Newton matrix H + A'DA is banded once its variables are
// ordered by knot; band storage costs n (b + 1) numbers and n b^2 / 2 multiply-adds to factorise
// instead of n^2 and n^3 / 6. With b = n - 1 it is the dense Cholesky factorisation, so a wide
// band is still correct, only not faster. Storage only grows: refactorising at the same or a
// smaller size and band allocates nothing.
//
//   BandCholesky k;
//   k.Resize(n, b);  k.SetZero();
//   k.Add(i, j, v);             // lower triangle: i >= j, i - j <= b
//   k.Factorize();  k.Solve(rhs);   // rhs: n values, overwritten with the solution
#pragma once

#include <cstddef>
#include <vector>

namespace stairplan::optim {

/// Band Cholesky factorisation in place (see the file's top comment).
class BandCholesky {
 public:
  /// Sizes for an n x n matrix of half-bandwidth `bandwidth` (allocates only to grow).
  void Resize(int n, int bandwidth);
  /// Zeroes the band (before adding a new matrix's entries).
  void SetZero();
  /// Adds `value` to entry (i, j) of the lower triangle (i >= j, i - j <= bandwidth()).
  void Add(int i, int j, double value) { band_[Index(i, j)] += value; }
  /// Factorises in place. A pivot d_j at or below `pivot_tol` times the largest diagonal entry
  /// (a singular or indefinite direction) is replaced by a huge one, so that the solution's
  /// component there comes out (nearly) zero; returns how many were replaced.
  int Factorize(double pivot_tol);
  /// Solves L D L' x = rhs in place (rhs has n values).
  void Solve(double* rhs) const;

  /// Where entry (i, j) of the lower triangle (i >= j, i - j <= bandwidth()) lives in data():
  /// for callers that add the same pattern many times and look its places up once.
  std::size_t Offset(int i, int j) const { return Index(i, j); }
  /// The band storage (n (bandwidth() + 1) values).
  double* data() { return band_.data(); }

  int size() const { return n_; }  ///< n
  int bandwidth() const { return b_; }  ///< the half-bandwidth b

 private:
  // Column j's entries (j..j+b) are stored together, the diagonal first (after Factorize: d_j,
  // then L's column below its unit diagonal).
  std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(b_ + 1) + static_cast<std::size_t>(i - j);
  }

  int n_ = 0, b_ = 0;
  std::vector<double> band_;
  // 1 / d_j: the solves multiply by it (a division per row was most of a solve's time).
  std::vector<double> inverse_pivot_;
};

}  // namespace stairplan::optim
