// The Ipopt back-end: a TNLP view of a Program (sparse linear rows, dense nonlinear blocks, and the
// Lagrangian's Hessian from the quadratic part plus the nonlinear parts' block pairs when they have one).
#include "stairplan/solvers/ipopt_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>

namespace stairplan::optim {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// Ipopt's "infinite" bound (nlp_lower_bound_inf / nlp_upper_bound_inf defaults).
constexpr double kIpoptInf = 1e19;

double ToIpopt(double b) { return std::isfinite(b) ? b : (b > 0 ? kIpoptInf : -kIpoptInf); }

class ProgramNlp : public Ipopt::TNLP {
 public:
  ProgramNlp(const Program& p, bool exact_hessian, std::chrono::steady_clock::time_point deadline, bool has_deadline,
             const IpoptDualGuess* duals)
      : p_(p), exact_hessian_(exact_hessian), deadline_(deadline), has_deadline_(has_deadline), duals_(duals) {
    n_ = p.num_variables();
    m_lin_ = p.num_rows();
    m_ = m_lin_ + p.num_nonlinear_rows();
    const Eigen::MatrixXd& A = p.constraint_matrix();
    for (int i = 0; i < m_lin_; ++i) {
      for (int j = 0; j < n_; ++j) {
        if (A(i, j) != 0.0) jac_entries_.push_back({i, j});
      }
    }
    int row = m_lin_;
    for (const auto& c : p.nonlinear_constraints()) {
      for (const auto& b : c.blocks) {
        for (int r = 0; r < c.lower.size(); ++r) {
          for (int j = 0; j < b.size; ++j) jac_entries_.push_back({row + r, b.start + j});
        }
      }
      row += static_cast<int>(c.lower.size());
    }
    const Eigen::MatrixXd& H = p.hessian();
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j <= i; ++j) {
        if (H(i, j) != 0.0) hess_entries_.push_back({i, j});
      }
    }
    quadratic_entries_ = hess_entries_.size();
    if (exact_hessian_ && !p.IsQuadratic()) AddNonlinearHessianParts();
    x_.resize(n_);
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = n_;
    m = m_;
    nnz_jac_g = static_cast<Index>(jac_entries_.size());
    nnz_h_lag = exact_hessian_ ? static_cast<Index>(hess_entries_.size()) : 0;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    for (int j = 0; j < n_; ++j) {
      x_l[j] = ToIpopt(p_.variable_lower()[j]);
      x_u[j] = ToIpopt(p_.variable_upper()[j]);
    }
    for (int i = 0; i < m_lin_; ++i) {
      g_l[i] = ToIpopt(p_.row_lower()[i]);
      g_u[i] = ToIpopt(p_.row_upper()[i]);
    }
    int row = m_lin_;
    for (const auto& c : p_.nonlinear_constraints()) {
      for (int r = 0; r < c.lower.size(); ++r, ++row) {
        g_l[row] = ToIpopt(c.lower[r]);
        g_u[row] = ToIpopt(c.upper[r]);
      }
    }
    return true;
  }

  bool get_starting_point(Index n, bool, Number* x, bool init_z, Number* z_L, Number* z_U, Index m, bool init_lambda,
                          Number* lambda) override {
    for (int j = 0; j < n; ++j) x[j] = p_.initial_guess()[j];
    if ((init_z || init_lambda) && duals_ == nullptr) return false;  // warm start asked through an option alone
    if (init_z) {
      // Ipopt's z_L, z_U >= 0 from one signed dual per variable (SolveResult's convention).
      for (int j = 0; j < n; ++j) {
        z_L[j] = std::max(0.0, -duals_->bound_duals[j]);
        z_U[j] = std::max(0.0, duals_->bound_duals[j]);
      }
    }
    if (init_lambda) {
      for (int i = 0; i < m_lin_; ++i) lambda[i] = duals_->row_duals[i];
      for (int i = m_lin_; i < m; ++i) lambda[i] = duals_->nonlinear_duals[i - m_lin_];
    }
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj) override {
    Load(x);
    obj = p_.Objective(x_);
    return std::isfinite(obj);
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    Load(x);
    Eigen::Map<Eigen::VectorXd> out(grad, n_);
    out.noalias() = p_.hessian() * x_;
    out += p_.linear_cost();
    for (const auto& c : p_.nonlinear_costs()) {
      for (int b = 0; b < static_cast<int>(c.blocks.size()); ++b) {
        Eigen::VectorXd part(c.blocks[b].size);
        c.gradient(x_, b, part);
        out.segment(c.blocks[b].start, c.blocks[b].size) += part;
      }
    }
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    Load(x);
    Eigen::Map<Eigen::VectorXd> out(g, m_);
    if (m_lin_ > 0) out.head(m_lin_).noalias() = p_.constraint_matrix() * x_;
    int row = m_lin_;
    for (const auto& c : p_.nonlinear_constraints()) {
      const int rows = static_cast<int>(c.lower.size());
      Eigen::VectorXd values(rows);
      c.value(x_, values);
      out.segment(row, rows) = values;
      row += rows;
    }
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* i_row, Index* j_col, Number* values) override {
    if (values == nullptr) {
      for (std::size_t k = 0; k < jac_entries_.size(); ++k) {
        i_row[k] = jac_entries_[k].first;
        j_col[k] = jac_entries_[k].second;
      }
      return true;
    }
    Load(x);
    std::size_t k = 0;
    const Eigen::MatrixXd& A = p_.constraint_matrix();
    for (; k < jac_entries_.size() && jac_entries_[k].first < m_lin_; ++k) {
      values[k] = A(jac_entries_[k].first, jac_entries_[k].second);
    }
    for (const auto& c : p_.nonlinear_constraints()) {
      const int rows = static_cast<int>(c.lower.size());
      for (int b = 0; b < static_cast<int>(c.blocks.size()); ++b) {
        Eigen::MatrixXd jac(rows, c.blocks[b].size);
        c.jacobian(x_, b, jac);
        // Entries were listed row-major per block.
        for (int r = 0; r < rows; ++r) {
          for (int j = 0; j < c.blocks[b].size; ++j) values[k++] = jac(r, j);
        }
      }
    }
    return true;
  }

  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index m, const Number* lambda, bool, Index,
              Index* i_row, Index* j_col, Number* values) override {
    if (!exact_hessian_) return false;
    if (values == nullptr) {
      for (std::size_t k = 0; k < hess_entries_.size(); ++k) {
        i_row[k] = hess_entries_[k].first;
        j_col[k] = hess_entries_[k].second;
      }
      return true;
    }
    for (std::size_t k = 0; k < hess_entries_.size(); ++k) values[k] = 0.0;
    for (std::size_t k = 0; k < quadratic_entries_; ++k) {
      values[k] = obj_factor * p_.hessian()(hess_entries_[k].first, hess_entries_[k].second);
    }
    if (hessian_parts_.empty()) return true;
    Load(x);
    const Eigen::Map<const Eigen::VectorXd> multipliers(lambda, m);
    for (HessianPart& part : hessian_parts_) {
      double factor = 1.0;
      if (part.constraint < 0) {
        p_.nonlinear_costs()[static_cast<std::size_t>(part.cost)].hessian(x_, part.a, part.b, part.out);
        factor = obj_factor;
      } else {
        const NonlinearConstraint& c = p_.nonlinear_constraints()[static_cast<std::size_t>(part.constraint)];
        c.hessian(x_, multipliers.segment(part.first_row, c.lower.size()), part.a, part.b, part.out);
      }
      for (Eigen::Index k = 0; k < part.out.size(); ++k) {
        const int slot = part.slots[static_cast<std::size_t>(k)];
        if (slot >= 0) values[slot] += factor * part.out.data()[k];
      }
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number* z_L, const Number* z_U,
                         Index m, const Number*, const Number* lambda, Number obj_value, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    status_ = status;
    x_out_ = Eigen::Map<const Eigen::VectorXd>(x, n);
    bound_duals_ = Eigen::Map<const Eigen::VectorXd>(z_U, n) - Eigen::Map<const Eigen::VectorXd>(z_L, n);
    row_duals_ = Eigen::Map<const Eigen::VectorXd>(lambda, m).head(m_lin_);
    nonlinear_duals_ = Eigen::Map<const Eigen::VectorXd>(lambda, m).tail(m - m_lin_);
    objective_ = obj_value;
    finalized_ = true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number, Number, Number,
                             Number, Index, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    if (has_deadline_ && std::chrono::steady_clock::now() > deadline_) {
      deadline_hit_ = true;
      return false;
    }
    return true;
  }

  bool finalized_ = false;
  bool deadline_hit_ = false;
  Ipopt::SolverReturn status_ = Ipopt::UNASSIGNED;
  Eigen::VectorXd x_out_, bound_duals_, row_duals_, nonlinear_duals_;
  double objective_ = 0.0;

 private:
  // One block pair of a nonlinear part's Hessian: its callback's output and where each of its
  // entries (column-major) lands in Ipopt's values, -1 for the upper triangle of a diagonal block.
  struct HessianPart {
    int cost = -1, constraint = -1;  // exactly one is an index
    int first_row = 0;               // a constraint's first row among Ipopt's constraints
    int a = 0, b = 0;
    Eigen::MatrixXd out;
    std::vector<int> slots;
  };

  // The Hessian of the Lagrangian: the quadratic part's entries first, then every (row, col) of
  // the lower triangle a nonlinear part's block pairs touch, each entry listed once.
  void AddNonlinearHessianParts() {
    std::map<std::pair<int, int>, int> slot_of;
    for (std::size_t k = 0; k < hess_entries_.size(); ++k) slot_of[hess_entries_[k]] = static_cast<int>(k);
    const auto add = [&](HessianPart part, const std::vector<VariableBlock>& blocks) {
      const VariableBlock& ba = blocks[static_cast<std::size_t>(part.a)];
      const VariableBlock& bb = blocks[static_cast<std::size_t>(part.b)];
      part.out.setZero(ba.size, bb.size);
      for (int c = 0; c < bb.size; ++c) {
        for (int r = 0; r < ba.size; ++r) {
          const int i = ba.start + r, j = bb.start + c;
          if (part.a == part.b && i < j) {
            part.slots.push_back(-1);
            continue;
          }
          const std::pair<int, int> entry(std::max(i, j), std::min(i, j));
          const auto [it, added] = slot_of.emplace(entry, static_cast<int>(hess_entries_.size()));
          if (added) hess_entries_.push_back(entry);
          part.slots.push_back(it->second);
        }
      }
      hessian_parts_.push_back(std::move(part));
    };
    const auto& costs = p_.nonlinear_costs();
    for (std::size_t i = 0; i < costs.size(); ++i) {
      for (const auto& [a, b] : HessianPairs(costs[i].hessian_pairs, static_cast<int>(costs[i].blocks.size()))) {
        HessianPart part;
        part.cost = static_cast<int>(i);
        part.a = a;
        part.b = b;
        add(std::move(part), costs[i].blocks);
      }
    }
    const auto& constraints = p_.nonlinear_constraints();
    int row = m_lin_;
    for (std::size_t i = 0; i < constraints.size(); ++i) {
      const NonlinearConstraint& c = constraints[i];
      for (const auto& [a, b] : HessianPairs(c.hessian_pairs, static_cast<int>(c.blocks.size()))) {
        HessianPart part;
        part.constraint = static_cast<int>(i);
        part.first_row = row;
        part.a = a;
        part.b = b;
        add(std::move(part), c.blocks);
      }
      row += static_cast<int>(c.lower.size());
    }
  }

  void Load(const Number* x) { x_ = Eigen::Map<const Eigen::VectorXd>(x, n_); }

  const Program& p_;
  bool exact_hessian_;
  std::chrono::steady_clock::time_point deadline_;
  bool has_deadline_;
  const IpoptDualGuess* duals_;  // null: no dual warm start
  int n_ = 0, m_ = 0, m_lin_ = 0;
  std::vector<std::pair<int, int>> jac_entries_, hess_entries_;
  std::size_t quadratic_entries_ = 0;  // the first hess_entries_, from the program's H
  std::vector<HessianPart> hessian_parts_;
  Eigen::VectorXd x_;
};

SolveStatus ToStatus(Ipopt::SolverReturn r, bool deadline_hit) {
  switch (r) {
    case Ipopt::SUCCESS:
    case Ipopt::STOP_AT_ACCEPTABLE_POINT:
      return SolveStatus::kSolved;
    case Ipopt::MAXITER_EXCEEDED: return SolveStatus::kIterationLimit;
    case Ipopt::CPUTIME_EXCEEDED: return SolveStatus::kTimeLimit;
    case Ipopt::USER_REQUESTED_STOP: return deadline_hit ? SolveStatus::kTimeLimit : SolveStatus::kNumericalError;
    case Ipopt::LOCAL_INFEASIBILITY: return SolveStatus::kInfeasible;
    case Ipopt::DIVERGING_ITERATES: return SolveStatus::kUnbounded;
    case Ipopt::INVALID_NUMBER_DETECTED: return SolveStatus::kInvalidInput;
    default: return SolveStatus::kNumericalError;
  }
}

}  // namespace

void IpoptSettings::Validate() const {
  if (!(tolerance > 0)) throw std::invalid_argument("IpoptSettings::tolerance must be positive");
  if (max_iterations <= 0) throw std::invalid_argument("IpoptSettings::max_iterations must be positive");
  if (!(time_limit_s > 0)) throw std::invalid_argument("IpoptSettings::time_limit_s must be positive");
}

void IpoptSolver::SetDualGuess(IpoptDualGuess guess) {
  dual_guess_ = std::move(guess);
  has_dual_guess_ = true;
}

void IpoptSolver::CheckDualGuess(const Program& program) const {
  const auto check = [](const Eigen::VectorXd& v, int size, const char* field, const char* what) {
    if (v.size() != size) {
      throw std::invalid_argument(std::string("IpoptDualGuess::") + field + ": " + std::to_string(v.size()) +
                                  " entries for " + std::to_string(size) + " " + what);
    }
  };
  check(dual_guess_.row_duals, program.num_rows(), "row_duals", "linear rows");
  check(dual_guess_.nonlinear_duals, program.num_nonlinear_rows(), "nonlinear_duals", "nonlinear rows");
  check(dual_guess_.bound_duals, program.num_variables(), "bound_duals", "variables");
  const bool finite = dual_guess_.row_duals.allFinite() && dual_guess_.nonlinear_duals.allFinite() &&
                      dual_guess_.bound_duals.allFinite();
  if (!finite) throw std::invalid_argument("IpoptDualGuess: multipliers must be finite");
}

void IpoptSolver::DoSolve(const Program& program, SolveResult* result) {
  if (has_dual_guess_) CheckDualGuess(program);
  const auto start = std::chrono::steady_clock::now();
  const bool has_deadline = std::isfinite(settings_.time_limit_s);
  const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(has_deadline ? settings_.time_limit_s : 0.0));
  const bool exact = program.IsQuadratic() ? settings_.exact_hessian_for_qp
                                           : settings_.exact_hessian_for_nlp && program.HasHessians();
  Ipopt::SmartPtr<ProgramNlp> nlp =
      new ProgramNlp(program, exact, deadline, has_deadline, has_dual_guess_ ? &dual_guess_ : nullptr);
  // No console journal: the library never prints (Ipopt would report bad options on stdout).
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(/*create_console_out=*/false);
  auto& options = *app->Options();
  options.SetStringValue("sb", "yes");
  options.SetIntegerValue("print_level", 0);
  options.SetNumericValue("tol", settings_.tolerance);
  options.SetIntegerValue("max_iter", settings_.max_iterations);
  if (has_deadline) options.SetNumericValue("max_cpu_time", settings_.time_limit_s);
  if (exact && program.IsQuadratic()) {
    options.SetStringValue("hessian_constant", "yes");
    options.SetStringValue("jac_c_constant", "yes");
    options.SetStringValue("jac_d_constant", "yes");
  } else if (!exact) {
    options.SetStringValue("hessian_approximation", "limited-memory");
  }
  if (has_dual_guess_) options.SetStringValue("warm_start_init_point", "yes");
  bool options_ok = true;
  for (const auto& [key, value] : settings_.string_options) options_ok &= options.SetStringValue(key, value);
  for (const auto& [key, value] : settings_.numeric_options) options_ok &= options.SetNumericValue(key, value);
  for (const auto& [key, value] : settings_.integer_options) options_ok &= options.SetIntegerValue(key, value);
  if (!options_ok || app->Initialize() != Ipopt::Solve_Succeeded) {
    result->status = SolveStatus::kInvalidInput;  // an option Ipopt rejects
    result->x = program.initial_guess();
    result->nonlinear_duals.resize(0);
    return;
  }
  app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  if (!nlp->finalized_) {
    result->status = SolveStatus::kNumericalError;
    result->x = program.initial_guess();
    result->nonlinear_duals.resize(0);
    return;
  }
  result->status = ToStatus(nlp->status_, nlp->deadline_hit_);
  result->x = nlp->x_out_;
  result->bound_duals = nlp->bound_duals_;
  result->row_duals = nlp->row_duals_;
  result->nonlinear_duals = nlp->nonlinear_duals_;
  result->objective = program.Objective(result->x);
  result->info.primal_residual = program.MaxViolation(result->x);
  Eigen::VectorXd residual = program.hessian() * result->x + program.linear_cost() + result->bound_duals;
  if (program.num_rows() > 0) residual += program.constraint_matrix().transpose() * result->row_duals;
  result->info.dual_residual = program.IsQuadratic() ? residual.lpNorm<Eigen::Infinity>() : 0.0;
  if (Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics(); IsValid(stats)) {
    result->info.iterations = stats->IterationCount();
  }
}

}  // namespace stairplan::optim
