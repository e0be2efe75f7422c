// Program: building, in-place updates with their checks, and evaluation helpers.
#include "stairplan/optim/program.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace stairplan::optim {
namespace {

// Revisions are unique across all programs, so a solver never mistakes one program for another.
std::uint64_t NextRevision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

bool AllFinite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }

bool NoNan(const Eigen::Ref<const Eigen::VectorXd>& v) { return !v.hasNaN(); }

void CheckBoundPair(const Eigen::Ref<const Eigen::VectorXd>& lower, const Eigen::Ref<const Eigen::VectorXd>& upper,
                    int size, const std::string& what) {
  if (lower.size() != size || upper.size() != size) {
    throw std::invalid_argument(what + ": bounds must have size " + std::to_string(size) + " (got " +
                                std::to_string(lower.size()) + " and " + std::to_string(upper.size()) + ")");
  }
  if (!NoNan(lower) || !NoNan(upper)) throw std::invalid_argument(what + ": bounds contain NaN");
  for (int i = 0; i < size; ++i) {
    if (NormalizeBound(lower[i]) > NormalizeBound(upper[i])) {
      throw std::invalid_argument(what + ": lower bound above upper bound at index " + std::to_string(i));
    }
  }
}

// Hessian pairs name blocks of their own cost or constraint, in the lower triangle (b <= a).
void CheckHessianPairs(const std::vector<std::pair<int, int>>& pairs, bool has_hessian, int blocks,
                       const std::string& what) {
  if (!pairs.empty() && !has_hessian) throw std::invalid_argument(what + ": hessian_pairs without a hessian");
  for (const auto& [a, b] : pairs) {
    if (!(0 <= b && b <= a && a < blocks)) {
      throw std::invalid_argument(what + ": hessian_pairs entry (" + std::to_string(a) + ", " + std::to_string(b) +
                                  ") must be block indices with b <= a < " + std::to_string(blocks));
    }
  }
}

}  // namespace

std::vector<std::pair<int, int>> HessianPairs(const std::vector<std::pair<int, int>>& pairs, int blocks) {
  if (!pairs.empty()) return pairs;
  std::vector<std::pair<int, int>> all;
  for (int a = 0; a < blocks; ++a) {
    for (int b = 0; b <= a; ++b) all.emplace_back(a, b);
  }
  return all;
}

void Program::TouchHessian() { hessian_revision_ = NextRevision(); }
void Program::TouchMatrix() {
  matrix_revision_ = NextRevision();
  whole_matrix_revision_ = matrix_revision_;
  const std::size_t m = static_cast<std::size_t>(A_.rows());
  row_revision_.resize(m);  // these allocate only when rows were added
  row_whole_revision_.resize(m);
  written_columns_.resize(m);
  written_count_.resize(m);
  std::fill(row_revision_.begin(), row_revision_.end(), matrix_revision_);
  std::fill(row_whole_revision_.begin(), row_whole_revision_.end(), matrix_revision_);
  std::fill(written_count_.begin(), written_count_.end(), 0);
}

bool Program::WrittenColumns(int k, std::uint64_t seen, const int** columns, int* count) const {
  const std::size_t row = static_cast<std::size_t>(k);
  if (row >= row_whole_revision_.size() || row_whole_revision_[row] > seen || written_count_[row] > kTrackedColumns) {
    return false;
  }
  *columns = written_columns_[row].data();
  *count = written_count_[row];
  return true;
}

void Program::CheckBlock(const VariableBlock& block, const char* what) const {
  if (block.start < 0 || block.size < 0 || block.start + block.size > num_variables()) {
    throw std::invalid_argument(std::string(what) + ": variable block '" + block.name + "' is not in this program");
  }
}

void Program::CheckRows(const ConstraintRows& rows, const char* what) const {
  if (rows.start < 0 || rows.size < 0 || rows.start + rows.size > num_rows()) {
    throw std::invalid_argument(std::string(what) + ": constraint rows '" + rows.name + "' are not in this program");
  }
}

VariableBlock Program::AddVariables(const std::string& name, int size) {
  if (size <= 0) throw std::invalid_argument("AddVariables: block '" + name + "' needs a positive size");
  const int n = num_variables();
  const int m = num_rows();
  VariableBlock block{name, n, size};
  blocks_.push_back(block);
  H_.conservativeResize(n + size, n + size);
  H_.rightCols(size).setZero();
  H_.bottomRows(size).setZero();
  g_.conservativeResize(n + size);
  g_.tail(size).setZero();
  A_.conservativeResize(m, n + size);
  A_.rightCols(size).setZero();
  var_lower_.conservativeResize(n + size);
  var_lower_.tail(size).setConstant(-kInf);
  var_upper_.conservativeResize(n + size);
  var_upper_.tail(size).setConstant(kInf);
  x0_.conservativeResize(n + size);
  x0_.tail(size).setZero();
  TouchHessian();
  TouchMatrix();
  return block;
}

void Program::ResizeDense(int n, int m) {
  if (n <= 0 || m < 0) throw std::invalid_argument("ResizeDense: sizes must be positive");
  blocks_.assign(1, VariableBlock{"x", 0, n});
  row_groups_.assign(1, ConstraintRows{"rows", 0, m});
  H_.setZero(n, n);
  g_.setZero(n);
  A_.setZero(m, n);
  row_lower_.setConstant(m, -kInf);
  row_upper_.setConstant(m, kInf);
  var_lower_.setConstant(n, -kInf);
  var_upper_.setConstant(n, kInf);
  x0_.setZero(n);
  constant_ = 0.0;
  TouchHessian();
  TouchMatrix();
}

void Program::AddQuadraticCost(const VariableBlock& block, const Eigen::MatrixXd& Q, const Eigen::VectorXd& g) {
  CheckBlock(block, "AddQuadraticCost");
  if (Q.rows() != block.size || Q.cols() != block.size || g.size() != block.size) {
    throw std::invalid_argument("AddQuadraticCost: Q and g must match block '" + block.name + "' (size " +
                                std::to_string(block.size) + ")");
  }
  if (!AllFinite(Q) || !AllFinite(g)) throw std::invalid_argument("AddQuadraticCost: non-finite data for '" + block.name + "'");
  // Store the symmetric part: only it matters for the cost, and the solvers rely on symmetry.
  H_.block(block.start, block.start, block.size, block.size) += 0.5 * (Q + Q.transpose());
  g_.segment(block.start, block.size) += g;
  TouchHessian();
}

void Program::AddCrossQuadraticCost(const VariableBlock& a, const VariableBlock& b, const Eigen::MatrixXd& Q) {
  CheckBlock(a, "AddCrossQuadraticCost");
  CheckBlock(b, "AddCrossQuadraticCost");
  if (Q.rows() != a.size || Q.cols() != b.size) {
    throw std::invalid_argument("AddCrossQuadraticCost: Q must be " + a.name + " x " + b.name + " sized");
  }
  if (!AllFinite(Q)) throw std::invalid_argument("AddCrossQuadraticCost: non-finite data");
  H_.block(a.start, b.start, a.size, b.size) += Q;
  H_.block(b.start, a.start, b.size, a.size) += Q.transpose();
  TouchHessian();
}

void Program::AddLinearCost(const VariableBlock& block, const Eigen::VectorXd& g) {
  CheckBlock(block, "AddLinearCost");
  if (g.size() != block.size || !AllFinite(g)) {
    throw std::invalid_argument("AddLinearCost: g must be finite and match block '" + block.name + "'");
  }
  g_.segment(block.start, block.size) += g;
}

ConstraintRows Program::AddLinearConstraint(const std::vector<LinearTerm>& terms, const Eigen::VectorXd& lower,
                                            const Eigen::VectorXd& upper, const std::string& name) {
  const int rows = static_cast<int>(lower.size());
  const std::string what = "AddLinearConstraint '" + name + "'";
  if (rows == 0) throw std::invalid_argument(what + ": no rows");
  CheckBoundPair(lower, upper, rows, what);
  for (const auto& [block, coeffs] : terms) {
    CheckBlock(block, "AddLinearConstraint");
    if (coeffs.rows() != rows || coeffs.cols() != block.size) {
      throw std::invalid_argument(what + ": coefficients of block '" + block.name + "' must be " +
                                  std::to_string(rows) + " x " + std::to_string(block.size));
    }
    if (!AllFinite(coeffs)) throw std::invalid_argument(what + ": non-finite coefficients for '" + block.name + "'");
  }
  const int m = num_rows();
  A_.conservativeResize(m + rows, num_variables());
  A_.bottomRows(rows).setZero();
  for (const auto& [block, coeffs] : terms) A_.block(m, block.start, rows, block.size) += coeffs;
  row_lower_.conservativeResize(m + rows);
  row_upper_.conservativeResize(m + rows);
  for (int i = 0; i < rows; ++i) {
    row_lower_[m + i] = NormalizeBound(lower[i]);
    row_upper_[m + i] = NormalizeBound(upper[i]);
  }
  ConstraintRows group{name, m, rows};
  row_groups_.push_back(group);
  TouchMatrix();
  return group;
}

void Program::AddNonlinearCost(NonlinearCost cost) {
  if (!cost.value || !cost.gradient) throw std::invalid_argument("AddNonlinearCost '" + cost.name + "': value and gradient are required");
  for (const auto& b : cost.blocks) CheckBlock(b, "AddNonlinearCost");
  CheckHessianPairs(cost.hessian_pairs, static_cast<bool>(cost.hessian), static_cast<int>(cost.blocks.size()),
                    "AddNonlinearCost '" + cost.name + "'");
  nonlinear_costs_.push_back(std::move(cost));
}

void Program::AddNonlinearConstraint(NonlinearConstraint constraint) {
  const std::string what = "AddNonlinearConstraint '" + constraint.name + "'";
  if (!constraint.value || !constraint.jacobian) throw std::invalid_argument(what + ": value and jacobian are required");
  for (const auto& b : constraint.blocks) CheckBlock(b, "AddNonlinearConstraint");
  CheckBoundPair(constraint.lower, constraint.upper, static_cast<int>(constraint.lower.size()), what);
  CheckHessianPairs(constraint.hessian_pairs, static_cast<bool>(constraint.hessian),
                    static_cast<int>(constraint.blocks.size()), what);
  for (int i = 0; i < constraint.lower.size(); ++i) {
    constraint.lower[i] = NormalizeBound(constraint.lower[i]);
    constraint.upper[i] = NormalizeBound(constraint.upper[i]);
  }
  nonlinear_constraints_.push_back(std::move(constraint));
}

void Program::SetVariableBounds(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& lower,
                                const Eigen::Ref<const Eigen::VectorXd>& upper) {
  CheckBlock(block, "SetVariableBounds");
  if (lower.size() != block.size || upper.size() != block.size || lower.hasNaN() || upper.hasNaN()) {
    throw std::invalid_argument("SetVariableBounds: bounds of block '" + block.name + "' have the wrong size or NaN");
  }
  for (int i = 0; i < block.size; ++i) {
    const double lo = NormalizeBound(lower[i]), hi = NormalizeBound(upper[i]);
    if (lo > hi) throw std::invalid_argument("SetVariableBounds: lower above upper in block '" + block.name + "'");
    var_lower_[block.start + i] = lo;
    var_upper_[block.start + i] = hi;
  }
}

void Program::SetLinearCost(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& g) {
  CheckBlock(block, "SetLinearCost");
  if (g.size() != block.size || !g.allFinite()) {
    throw std::invalid_argument("SetLinearCost: g of block '" + block.name + "' has the wrong size or is not finite");
  }
  g_.segment(block.start, block.size) = g;
}

void Program::SetConstraintBounds(const ConstraintRows& rows, const Eigen::Ref<const Eigen::VectorXd>& lower,
                                  const Eigen::Ref<const Eigen::VectorXd>& upper) {
  CheckRows(rows, "SetConstraintBounds");
  if (lower.size() != rows.size || upper.size() != rows.size || lower.hasNaN() || upper.hasNaN()) {
    throw std::invalid_argument("SetConstraintBounds: bounds of rows '" + rows.name + "' have the wrong size or NaN");
  }
  for (int i = 0; i < rows.size; ++i) {
    const double lo = NormalizeBound(lower[i]), hi = NormalizeBound(upper[i]);
    if (lo > hi) throw std::invalid_argument("SetConstraintBounds: lower above upper in rows '" + rows.name + "'");
    row_lower_[rows.start + i] = lo;
    row_upper_[rows.start + i] = hi;
  }
}

void Program::SetConstraintCoefficients(const ConstraintRows& rows, const VariableBlock& block,
                                        const Eigen::Ref<const Eigen::MatrixXd>& coefficients) {
  CheckRows(rows, "SetConstraintCoefficients");
  CheckBlock(block, "SetConstraintCoefficients");
  if (coefficients.rows() != rows.size || coefficients.cols() != block.size || !coefficients.allFinite()) {
    throw std::invalid_argument("SetConstraintCoefficients: coefficients for rows '" + rows.name + "' and block '" +
                                block.name + "' have the wrong size or are not finite");
  }
  A_.block(rows.start, block.start, rows.size, block.size) = coefficients;
  // Only these rows changed: solvers keep what depends on the others (the active-set solver its
  // factorisation, when none of these rows is active).
  if (row_revision_.size() != static_cast<std::size_t>(A_.rows())) return TouchMatrix();  // resized behind our back
  matrix_revision_ = NextRevision();
  for (int k = rows.start; k < rows.start + rows.size; ++k) {
    row_revision_[static_cast<std::size_t>(k)] = matrix_revision_;
    row_whole_revision_[static_cast<std::size_t>(k)] = matrix_revision_;
  }
}

void Program::SetConstraintCoefficient(const ConstraintRows& rows, int row, const VariableBlock& block, int index,
                                       double value) {
  CheckRows(rows, "SetConstraintCoefficient");
  CheckBlock(block, "SetConstraintCoefficient");
  if (row < 0 || row >= rows.size || index < 0 || index >= block.size || !std::isfinite(value)) {
    throw std::invalid_argument("SetConstraintCoefficient: row " + std::to_string(row) + " of '" + rows.name +
                                "' or variable " + std::to_string(index) + " of '" + block.name +
                                "' is outside them, or the value is not finite");
  }
  const int k = rows.start + row;
  const int column = block.start + index;
  A_(k, column) = value;
  if (row_revision_.size() != static_cast<std::size_t>(A_.rows())) return TouchMatrix();  // resized behind our back
  matrix_revision_ = NextRevision();
  row_revision_[static_cast<std::size_t>(k)] = matrix_revision_;
  TrackWrittenColumn(k, column);
}

void Program::SetRowCoefficients(const ConstraintRows& rows, int row, const Coefficient* coefficients, int count) {
  CheckRows(rows, "SetRowCoefficients");
  if (row < 0 || row >= rows.size || count < 0 || (count > 0 && coefficients == nullptr)) {
    throw std::invalid_argument("SetRowCoefficients: row " + std::to_string(row) + " of '" + rows.name +
                                "' is outside them, or the coefficients are missing");
  }
  for (int i = 0; i < count; ++i) {
    if (coefficients[i].column < 0 || coefficients[i].column >= num_variables() || !std::isfinite(coefficients[i].value)) {
      throw std::invalid_argument("SetRowCoefficients: coefficient " + std::to_string(i) + " of row " +
                                  std::to_string(row) + " of '" + rows.name +
                                  "' is outside the variables, or its value is not finite");
    }
  }
  if (count == 0) return;
  const int k = rows.start + row;
  for (int i = 0; i < count; ++i) A_(k, coefficients[i].column) = coefficients[i].value;
  if (row_revision_.size() != static_cast<std::size_t>(A_.rows())) return TouchMatrix();  // resized behind our back
  matrix_revision_ = NextRevision();
  row_revision_[static_cast<std::size_t>(k)] = matrix_revision_;
  for (int i = 0; i < count; ++i) TrackWrittenColumn(k, coefficients[i].column);
}

void Program::TrackWrittenColumn(int k, int column) {
  // The column joins the row's written ones, kept ascending.
  int& count = written_count_[static_cast<std::size_t>(k)];
  if (count > kTrackedColumns) return;
  std::array<int, kTrackedColumns>& written = written_columns_[static_cast<std::size_t>(k)];
  int at = 0;
  while (at < count && written[static_cast<std::size_t>(at)] < column) ++at;
  if (at < count && written[static_cast<std::size_t>(at)] == column) return;
  if (count == kTrackedColumns) {
    count = kTrackedColumns + 1;
    return;
  }
  for (int i = count; i > at; --i) written[static_cast<std::size_t>(i)] = written[static_cast<std::size_t>(i - 1)];
  written[static_cast<std::size_t>(at)] = column;
  ++count;
}

void Program::SetInitialGuess(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& x0) {
  CheckBlock(block, "SetInitialGuess");
  if (x0.size() != block.size || !x0.allFinite()) {
    throw std::invalid_argument("SetInitialGuess: guess for block '" + block.name + "' has the wrong size or is not finite");
  }
  x0_.segment(block.start, block.size) = x0;
}

Eigen::MatrixXd& Program::MutableHessian() {
  TouchHessian();
  return H_;
}

Eigen::MatrixXd& Program::MutableConstraintMatrix() {
  TouchMatrix();
  return A_;
}

bool Program::HasHessians() const {
  for (const auto& c : nonlinear_costs_) {
    if (!c.hessian) return false;
  }
  for (const auto& c : nonlinear_constraints_) {
    if (!c.hessian) return false;
  }
  return true;
}

int Program::num_nonlinear_rows() const {
  int rows = 0;
  for (const auto& c : nonlinear_constraints_) rows += static_cast<int>(c.lower.size());
  return rows;
}

double Program::Objective(const Eigen::VectorXd& x) const {
  double f = 0.5 * x.dot(H_ * x) + g_.dot(x) + constant_;
  for (const auto& c : nonlinear_costs_) f += c.value(x);
  return f;
}

double Program::MaxViolation(const Eigen::VectorXd& x) const {
  double v = 0.0;
  const auto excess = [&v](double value, double lo, double hi) {
    if (lo > -kInf) v = std::max(v, lo - value);
    if (hi < kInf) v = std::max(v, value - hi);
  };
  for (int i = 0; i < num_variables(); ++i) excess(x[i], var_lower_[i], var_upper_[i]);
  if (num_rows() > 0) {
    const Eigen::VectorXd ax = A_ * x;
    for (int i = 0; i < num_rows(); ++i) excess(ax[i], row_lower_[i], row_upper_[i]);
  }
  for (const auto& c : nonlinear_constraints_) {
    Eigen::VectorXd values(c.lower.size());
    c.value(x, values);
    for (int i = 0; i < values.size(); ++i) excess(values[i], c.lower[i], c.upper[i]);
  }
  return v;
}

}  // namespace stairplan::optim
