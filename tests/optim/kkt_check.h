// The KKT conditions of a QP result in SolveResult's dual convention (H x + g + A'y + z = 0, a
// dual <= 0 where the lower side binds and >= 0 where the upper one does), checked with Catch2.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "stairplan/optim/program.h"
#include "stairplan/optim/solve_result.h"

namespace stairplan::testing {

/// Stationarity, feasibility, dual signs (none toward an infinite side) and complementarity,
/// each within `tol`.
inline void CheckKkt(const optim::Program& p, const optim::SolveResult& r, double tol) {
  const Eigen::VectorXd ax = p.constraint_matrix() * r.x;
  const Eigen::VectorXd stationarity =
      p.hessian() * r.x + p.linear_cost() + p.constraint_matrix().transpose() * r.row_duals + r.bound_duals;
  CHECK(stationarity.lpNorm<Eigen::Infinity>() < tol);
  CHECK(p.MaxViolation(r.x) < tol);
  const auto complementary = [&](double value, double lo, double hi, double dual) {
    if (!std::isfinite(lo)) CHECK(dual > -tol);  // no lower side: no push from below
    if (!std::isfinite(hi)) CHECK(dual < tol);
    if (std::isfinite(lo)) CHECK(std::abs(std::min(dual, 0.0) * (value - lo)) < tol * (1.0 + std::abs(dual)));
    if (std::isfinite(hi)) CHECK(std::abs(std::max(dual, 0.0) * (hi - value)) < tol * (1.0 + std::abs(dual)));
  };
  for (int i = 0; i < p.num_rows(); ++i) {
    complementary(ax[i], optim::NormalizeBound(p.row_lower()[i]), optim::NormalizeBound(p.row_upper()[i]),
                  r.row_duals[i]);
  }
  for (int j = 0; j < p.num_variables(); ++j) {
    complementary(r.x[j], optim::NormalizeBound(p.variable_lower()[j]), optim::NormalizeBound(p.variable_upper()[j]),
                  r.bound_duals[j]);
  }
}

}  // namespace stairplan::testing
