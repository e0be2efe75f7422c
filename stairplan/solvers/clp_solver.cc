// The CLP back-end: a Program's QP loaded into a ClpSimplex (sparse A by column, one triangle of
// H as CLP's quadratic objective), solved by the primal simplex or the barrier, and read back in
// SolveResult's conventions.
#include "stairplan/solvers/clp_solver.h"

#include <cmath>
#include <memory>
#include <vector>

#include <coin/ClpSimplex.hpp>
#include <coin/ClpSolve.hpp>
#include <coin/CoinFinite.hpp>

namespace stairplan::optim {
namespace {

double ToClp(double bound) { return std::isfinite(bound) ? bound : (bound > 0 ? COIN_DBL_MAX : -COIN_DBL_MAX); }

SolveStatus ToStatus(const ClpSimplex& clp) {
  switch (clp.status()) {
    // Secondary 2-4: optimal in CLP's scaled problem only, the unscaled one infeasible.
    case 0: return clp.secondaryStatus() >= 2 && clp.secondaryStatus() <= 4 ? SolveStatus::kNumericalError
                                                                            : SolveStatus::kSolved;
    case 1: return SolveStatus::kInfeasible;
    case 2: return SolveStatus::kUnbounded;
    case 3: return clp.secondaryStatus() == 9 ? SolveStatus::kTimeLimit : SolveStatus::kIterationLimit;
    default: return SolveStatus::kNumericalError;  // 4 errors, 5 event handler, -1 unknown
  }
}

// The side a dual's sign says is active (SolveResult's convention; equalities use -1).
ActiveSide SideOf(double dual, double lower, double upper) {
  if (dual == 0.0) return 0;
  if (lower == upper) return -1;
  return dual < 0 ? -1 : 1;
}

}  // namespace

struct ClpSolver::Model {
  std::unique_ptr<ClpSimplex> clp;
  int n = 0, m = 0;
  // The last solve's basis and solution, kept for a rebuilt model of the same size.
  std::vector<unsigned char> basis;
  std::vector<double> x;
  // +1, or -1 for a variable bounded above only: CLP 1.17's QP simplex and barrier called
  // min 0.5|x|^2 - x1 s.t. x1 + x2 >= 1, x <= 4 infeasible, and solve it as x' = -x >= -4.
  std::vector<double> sign;
  // Column-major nonzeros of A and of H's lower triangle (reused storage).
  std::vector<CoinBigIndex> start, q_start;
  std::vector<int> index, q_index;
  std::vector<double> value, q_value;
  std::vector<double> col_lower, col_upper, row_lower, row_upper, objective;

  static bool Flipped(const Program& p, int j) {
    return !std::isfinite(p.variable_lower()[j]) && std::isfinite(p.variable_upper()[j]);
  }
  void Load(const Program& p, const ClpSettings& s);
  void SaveBasis();
};

void ClpSolver::Model::Load(const Program& p, const ClpSettings& s) {
  n = p.num_variables();
  m = p.num_rows();
  sign.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) sign[static_cast<std::size_t>(j)] = Flipped(p, j) ? -1.0 : 1.0;
  const auto sign_of = [this](int j) { return sign[static_cast<std::size_t>(j)]; };
  const Eigen::MatrixXd& A = p.constraint_matrix();
  const Eigen::MatrixXd& H = p.hessian();
  start.assign(1, 0);
  index.clear();
  value.clear();
  q_start.assign(1, 0);
  q_index.clear();
  q_value.clear();
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < m; ++i) {
      if (A(i, j) == 0.0) continue;
      index.push_back(i);
      value.push_back(sign_of(j) * A(i, j));
    }
    start.push_back(static_cast<CoinBigIndex>(index.size()));
    for (int i = j; i < n; ++i) {
      if (H(i, j) == 0.0) continue;
      q_index.push_back(i);
      q_value.push_back(sign_of(i) * sign_of(j) * H(i, j));
    }
    q_start.push_back(static_cast<CoinBigIndex>(q_index.size()));
  }
  col_lower.resize(static_cast<std::size_t>(n));
  col_upper.resize(static_cast<std::size_t>(n));
  row_lower.resize(static_cast<std::size_t>(m));
  row_upper.resize(static_cast<std::size_t>(m));
  objective.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    col_lower[k] = ToClp(sign_of(j) > 0 ? p.variable_lower()[j] : -p.variable_upper()[j]);
    col_upper[k] = ToClp(sign_of(j) > 0 ? p.variable_upper()[j] : kInf);
    objective[k] = sign_of(j) * p.linear_cost()[j];
  }
  for (int i = 0; i < m; ++i) {
    row_lower[static_cast<std::size_t>(i)] = ToClp(p.row_lower()[i]);
    row_upper[static_cast<std::size_t>(i)] = ToClp(p.row_upper()[i]);
  }
  clp = std::make_unique<ClpSimplex>();
  clp->setLogLevel(0);
  clp->loadProblem(n, m, start.data(), index.data(), value.data(), col_lower.data(), col_upper.data(),
                  objective.data(), row_lower.data(), row_upper.data());
  if (!q_value.empty()) clp->loadQuadraticObjective(n, q_start.data(), q_index.data(), q_value.data());
  clp->setPrimalTolerance(s.primal_tolerance);
  clp->setDualTolerance(s.dual_tolerance);
  clp->setMaximumIterations(s.max_iterations);
  if (std::isfinite(s.time_limit_s)) clp->setMaximumSeconds(s.time_limit_s);
  // CLP's QP simplex on its scaled problem stopped where only that one was optimal (DPKLO1 at
  // 1.0885 for 0.3701) or did not converge (CVXQP1_S); unscaled it solves both. The barrier
  // keeps CLP's default scaling.
  if (s.algorithm == ClpAlgorithm::kPrimalSimplex) clp->scaling(0);
}

void ClpSolver::Model::SaveBasis() {
  const unsigned char* status = clp->statusArray();
  if (status == nullptr) return basis.clear();
  basis.assign(status, status + n + m);
  x.assign(clp->primalColumnSolution(), clp->primalColumnSolution() + n);
}

ClpSolver::ClpSolver() : model_(std::make_unique<Model>()) {}
ClpSolver::ClpSolver(const ClpSettings& settings) : settings_(settings), model_(std::make_unique<Model>()) {
  settings_.Validate();
}
ClpSolver::~ClpSolver() = default;

bool ClpSolver::IsAvailable() { return true; }

void ClpSolver::ResetWarmStart() { model_ = std::make_unique<Model>(); }

void ClpSolver::DoSolve(const Program& program, SolveResult* result) {
  settings_.Validate();
  Model& model = *model_;
  const int n = program.num_variables(), m = program.num_rows();
  const bool warm = settings_.warm_start && settings_.algorithm == ClpAlgorithm::kPrimalSimplex;
  const bool same_size = model.n == n && model.m == m;
  const std::vector<double> previous_sign = model.sign;
  model.Load(program, settings_);
  int iterations = 0;
  if (warm && same_size && model.sign == previous_sign && model.basis.size() == static_cast<std::size_t>(n + m)) {
    model.clp->copyinStatus(model.basis.data());
    model.clp->setColSolution(model.x.data());
    model.clp->primal();
    if (ToStatus(*model.clp) == SolveStatus::kSolved) {
      FillResult(program, model, result);
      return;
    }
    // From a kept basis CLP called feasible QPs infeasible (x1 + x2 >= 3 after >= 1, x <= 4):
    // a failed warm start is solved again from cold, as the active-set solver does.
    iterations = model.clp->numberIterations();
    ++result->info.cold_restarts;
    model.Load(program, settings_);
  }
  if (settings_.algorithm == ClpAlgorithm::kBarrier) {
    ClpSolve options;  // presolve, then ClpInterior with a KKT factorisation (barrier() has none for QPs)
    options.setSolveType(ClpSolve::useBarrier);
    model.clp->initialSolve(options);
  } else {
    model.clp->primal();
  }
  FillResult(program, model, result);
  result->info.iterations += iterations;
}

void ClpSolver::FillResult(const Program& program, Model& model, SolveResult* result) {
  const int n = program.num_variables(), m = program.num_rows();
  result->status = ToStatus(*model.clp);
  const Eigen::Map<const Eigen::VectorXd> sign(model.sign.data(), n);
  result->x = sign.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(model.clp->primalColumnSolution(), n));
  result->row_duals = -Eigen::Map<const Eigen::VectorXd>(model.clp->dualRowSolution(), m);
  result->bound_duals = -sign.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(model.clp->dualColumnSolution(), n));
  if (!result->x.allFinite() || !result->row_duals.allFinite() || !result->bound_duals.allFinite()) {
    result->status = SolveStatus::kNumericalError;
    result->x = program.initial_guess();
    result->row_duals.setZero();
    result->bound_duals.setZero();
  }
  for (int i = 0; i < m; ++i) {
    result->active_set.rows[static_cast<std::size_t>(i)] =
        SideOf(result->row_duals[i], program.row_lower()[i], program.row_upper()[i]);
  }
  for (int j = 0; j < n; ++j) {
    result->active_set.bounds[static_cast<std::size_t>(j)] =
        SideOf(result->bound_duals[j], program.variable_lower()[j], program.variable_upper()[j]);
  }
  result->objective = program.Objective(result->x);
  result->info.iterations = model.clp->numberIterations();
  result->info.primal_residual = program.MaxViolation(result->x);
  Eigen::VectorXd residual = program.hessian() * result->x + program.linear_cost() + result->bound_duals;
  if (m > 0) residual += program.constraint_matrix().transpose() * result->row_duals;
  result->info.dual_residual = residual.lpNorm<Eigen::Infinity>();
  if (settings_.warm_start && settings_.algorithm == ClpAlgorithm::kPrimalSimplex &&
      result->status == SolveStatus::kSolved) {
    model.SaveBasis();
  } else {
    model.basis.clear();  // cold next time: warm starts off, or this solve failed
  }
}

}  // namespace stairplan::optim
