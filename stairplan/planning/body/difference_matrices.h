// Finite-difference operators over a horizon's knots, shared by the body QP and the body NLP
// (their smoothness costs and acceleration limits are the same differences).
#pragma once

#include <Eigen/Dense>

namespace stairplan {

/// (n-1) x n first differences: row k is x[k+1] - x[k].
inline Eigen::MatrixXd FirstDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 1, n);
  for (int k = 0; k + 1 < n; ++k) d(k, k) = -1.0, d(k, k + 1) = 1.0;
  return d;
}

/// (n-2) x n second differences: row k is x[k] - 2 x[k+1] + x[k+2].
inline Eigen::MatrixXd SecondDifferences(int n) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n - 2, n);
  for (int k = 0; k + 2 < n; ++k) d(k, k) = 1.0, d(k, k + 1) = -2.0, d(k, k + 2) = 1.0;
  return d;
}

}  // namespace stairplan
