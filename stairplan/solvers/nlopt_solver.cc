// The NLopt back-end: objective with gradient, constraints gathered into two vector constraints.
#include "stairplan/solvers/nlopt_solver.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <nlopt.hpp>

namespace stairplan::optim {
namespace {

// All constraints of a program as g(x) <= 0 (inequalities) and h(x) = 0 (equalities).
class ConstraintSet {
 public:
  ConstraintSet(const Program& p, const Eigen::VectorXd& scale) : p_(p), scale_(scale) {
    const auto add = [&](int source, double lo, double hi) {
      if (std::isfinite(lo) && lo == hi) {
        eq_.push_back({source, 1.0, lo});
        return;
      }
      if (std::isfinite(lo)) ineq_.push_back({source, -1.0, lo});  // lo - v <= 0
      if (std::isfinite(hi)) ineq_.push_back({source, 1.0, hi});   // v - hi <= 0
    };
    for (int i = 0; i < p.num_rows(); ++i) add(i, p.row_lower()[i], p.row_upper()[i]);
    int row = p.num_rows();
    for (const auto& c : p.nonlinear_constraints()) {
      for (int r = 0; r < c.lower.size(); ++r) add(row + r, c.lower[r], c.upper[r]);
      row += static_cast<int>(c.lower.size());
    }
    values_.resize(row);
    jacobian_.resize(row, p.num_variables());
  }

  struct Entry {
    int source;     // row index in the stacked [A; c(x)]
    double sign;    // +1: v - bound, -1: bound - v
    double bound;
  };

  // Evaluates the stacked values (and Jacobian when grad != nullptr) at x.
  void Evaluate(const double* x, bool with_jacobian) {
    const int n = p_.num_variables();
    x_ = scale_.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, n));
    const int m = p_.num_rows();
    if (m > 0) values_.head(m).noalias() = p_.constraint_matrix() * x_;
    if (with_jacobian && m > 0) jacobian_.topRows(m) = p_.constraint_matrix();
    int row = m;
    for (const auto& c : p_.nonlinear_constraints()) {
      const int rows = static_cast<int>(c.lower.size());
      Eigen::VectorXd v(rows);
      c.value(x_, v);
      values_.segment(row, rows) = v;
      if (with_jacobian) {
        jacobian_.middleRows(row, rows).setZero();
        for (int b = 0; b < static_cast<int>(c.blocks.size()); ++b) {
          Eigen::MatrixXd jac(rows, c.blocks[b].size);
          c.jacobian(x_, b, jac);
          jacobian_.block(row, c.blocks[b].start, rows, c.blocks[b].size) += jac;
        }
      }
      row += rows;
    }
  }

  void Fill(const std::vector<Entry>& entries, double* result, double* grad) const {
    const int n = p_.num_variables();
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const Entry& e = entries[k];
      result[k] = e.sign * (values_[e.source] - e.bound);
      if (grad != nullptr) {
        for (int j = 0; j < n; ++j) grad[k * n + j] = e.sign * jacobian_(e.source, j) * scale_[j];
      }
    }
  }

  const Program& p_;
  const Eigen::VectorXd& scale_;  // x = scale .* (NLopt's variables)
  std::vector<Entry> ineq_, eq_;
  Eigen::VectorXd x_, values_;
  Eigen::MatrixXd jacobian_;
};

struct Context {
  const Program* program;
  ConstraintSet* constraints;
  const Eigen::VectorXd* scale;
  Eigen::VectorXd x, part;
  int evaluations = 0;
};

double Objective(unsigned n, const double* x, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  ++c.evaluations;
  const Program& p = *c.program;
  c.x = c.scale->cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, n));
  if (grad != nullptr) {
    Eigen::Map<Eigen::VectorXd> out(grad, n);
    out.noalias() = p.hessian() * c.x;
    out += p.linear_cost();
    for (const auto& cost : p.nonlinear_costs()) {
      for (int b = 0; b < static_cast<int>(cost.blocks.size()); ++b) {
        c.part.resize(cost.blocks[b].size);
        cost.gradient(c.x, b, c.part);
        out.segment(cost.blocks[b].start, cost.blocks[b].size) += c.part;
      }
    }
    out.array() *= c.scale->array();
  }
  return p.Objective(c.x);
}

void Inequalities(unsigned, double* result, unsigned, const double* x, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  c.constraints->Evaluate(x, grad != nullptr);
  c.constraints->Fill(c.constraints->ineq_, result, grad);
}

void Equalities(unsigned, double* result, unsigned, const double* x, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  c.constraints->Evaluate(x, grad != nullptr);
  c.constraints->Fill(c.constraints->eq_, result, grad);
}

// Per variable 1 / sqrt of the objective's curvature at the initial guess (the quadratic part and
// the nonlinear costs' Hessians where they have one), 1 where it is not positive: in these units
// SLSQP's first quasi-Newton matrix, the identity, is the Hessian's diagonal.
Eigen::VectorXd HessianScale(const Program& p) {
  Eigen::VectorXd diagonal = p.hessian().diagonal();
  const Eigen::VectorXd& x0 = p.initial_guess();
  for (const auto& cost : p.nonlinear_costs()) {
    if (!cost.hessian) continue;
    for (const auto& [a, b] : HessianPairs(cost.hessian_pairs, static_cast<int>(cost.blocks.size()))) {
      if (a != b) continue;
      const VariableBlock& block = cost.blocks[static_cast<std::size_t>(a)];
      Eigen::MatrixXd h = Eigen::MatrixXd::Zero(block.size, block.size);
      cost.hessian(x0, a, a, h);
      diagonal.segment(block.start, block.size) += h.diagonal();
    }
  }
  Eigen::VectorXd scale(diagonal.size());
  for (Eigen::Index j = 0; j < diagonal.size(); ++j) {
    scale[j] = diagonal[j] > 0.0 && std::isfinite(diagonal[j]) ? 1.0 / std::sqrt(diagonal[j]) : 1.0;
  }
  return scale;
}

}  // namespace

void NloptSettings::Validate() const {
  if (!(xtol_rel >= 0) || !(ftol_rel >= 0)) throw std::invalid_argument("NloptSettings::xtol_rel/ftol_rel must be >= 0");
  if (!(constraint_tol > 0)) throw std::invalid_argument("NloptSettings::constraint_tol must be positive");
  if (max_evaluations <= 0) throw std::invalid_argument("NloptSettings::max_evaluations must be positive");
  if (!(time_limit_s > 0)) throw std::invalid_argument("NloptSettings::time_limit_s must be positive");
}

void NloptSolver::DoSolve(const Program& program, SolveResult* result) {
  const int n = program.num_variables();
  const nlopt::algorithm algorithm =
      settings_.algorithm == NloptSettings::Algorithm::kSlsqp ? nlopt::LD_SLSQP : nlopt::LN_COBYLA;
  nlopt::opt opt(algorithm, static_cast<unsigned>(n));
  const Eigen::VectorXd scale = settings_.scale_by_hessian ? HessianScale(program) : Eigen::VectorXd::Ones(n);
  ConstraintSet constraints(program, scale);
  Context context{&program, &constraints, &scale, Eigen::VectorXd(n), Eigen::VectorXd(), 0};
  std::vector<double> lower(n), upper(n), x(n);
  for (int j = 0; j < n; ++j) {
    lower[j] = program.variable_lower()[j] / scale[j];
    upper[j] = program.variable_upper()[j] / scale[j];
    // NLopt requires a start within the bounds.
    x[j] = std::min(std::max(program.initial_guess()[j] / scale[j], lower[j]), upper[j]);
  }
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(Objective, &context);
  if (!constraints.ineq_.empty()) {
    opt.add_inequality_mconstraint(Inequalities, &context,
                                   std::vector<double>(constraints.ineq_.size(), settings_.constraint_tol));
  }
  if (!constraints.eq_.empty()) {
    opt.add_equality_mconstraint(Equalities, &context,
                                 std::vector<double>(constraints.eq_.size(), settings_.constraint_tol));
  }
  opt.set_xtol_rel(settings_.xtol_rel);
  opt.set_ftol_rel(settings_.ftol_rel);
  opt.set_maxeval(settings_.max_evaluations);
  if (std::isfinite(settings_.time_limit_s)) opt.set_maxtime(settings_.time_limit_s);
  double f = 0.0;
  nlopt::result code = nlopt::FAILURE;
  SolveStatus status = SolveStatus::kNumericalError;
  try {
    code = opt.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {
    code = nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    code = nlopt::FORCED_STOP;
  } catch (const std::invalid_argument&) {
    code = nlopt::INVALID_ARGS;
  } catch (const std::runtime_error&) {
    code = nlopt::FAILURE;
  }
  for (int j = 0; j < n; ++j) result->x[j] = scale[j] * x[j];
  const double violation = program.MaxViolation(result->x);
  const double feasible_tol = 1e-6 * (1.0 + result->x.lpNorm<Eigen::Infinity>());
  switch (code) {
    case nlopt::SUCCESS:
    case nlopt::STOPVAL_REACHED:
    case nlopt::FTOL_REACHED:
    case nlopt::XTOL_REACHED:
    case nlopt::ROUNDOFF_LIMITED:
      status = violation <= feasible_tol ? SolveStatus::kSolved : SolveStatus::kInfeasible;
      break;
    case nlopt::MAXEVAL_REACHED: status = SolveStatus::kIterationLimit; break;
    case nlopt::MAXTIME_REACHED: status = SolveStatus::kTimeLimit; break;
    case nlopt::INVALID_ARGS: status = SolveStatus::kInvalidInput; break;
    default: status = SolveStatus::kNumericalError; break;
  }
  result->status = status;
  result->row_duals.setZero();
  result->bound_duals.setZero();
  result->nonlinear_duals.resize(0);  // none: NLopt returns no multipliers
  result->objective = program.Objective(result->x);
  result->info.iterations = context.evaluations;
  result->info.primal_residual = violation;
}

}  // namespace stairplan::optim
