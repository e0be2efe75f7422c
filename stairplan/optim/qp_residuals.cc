// qpbenchmark's primal residual, dual residual and duality gap for a Program's QP.
#include "stairplan/optim/qp_residuals.h"

#include <cmath>
#include <stdexcept>

namespace stairplan::optim {

QpResiduals ComputeQpResiduals(const Program& p, const SolveResult& r) {
  const int n = p.num_variables(), m = p.num_rows();
  if (r.x.size() != n || r.row_duals.size() != m || r.bound_duals.size() != n) {
    throw std::invalid_argument("ComputeQpResiduals: the result's sizes do not match the program");
  }
  QpResiduals out;
  if (!r.x.allFinite()) return out;
  out.primal = p.MaxViolation(r.x);
  if (!r.row_duals.allFinite() || !r.bound_duals.allFinite()) return out;
  const Eigen::VectorXd hx = p.hessian() * r.x;
  Eigen::VectorXd stationarity = hx + p.linear_cost() + r.bound_duals;
  if (m > 0) stationarity += p.constraint_matrix().transpose() * r.row_duals;
  out.dual = stationarity.lpNorm<Eigen::Infinity>();
  double gap = r.x.dot(hx) + p.linear_cost().dot(r.x);
  for (int i = 0; i < m; ++i) gap += GapSupportTerm(r.row_duals[i], p.row_lower()[i], p.row_upper()[i]);
  for (int j = 0; j < n; ++j) gap += GapSupportTerm(r.bound_duals[j], p.variable_lower()[j], p.variable_upper()[j]);
  out.gap = std::isnan(gap) ? kInf : std::abs(gap);
  return out;
}

}  // namespace stairplan::optim
