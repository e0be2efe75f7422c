// Program: an optimisation problem built once and updated in place between solves.
//
// Continuous variables live in named blocks; costs are linear, quadratic or nonlinear; constraints
// are linear rows with lower/upper bounds or nonlinear functions with Jacobians per variable block
// (the ifopt idea, with block handles instead of string keys). The quadratic and linear parts are
// stored densely because the per-cycle problems are small (tens to a few hundred variables).
//
// Per-cycle usage (the body planner): build once, then update and re-solve without allocating.
//
//   Program prog;
//   const VariableBlock z = prog.AddVariables("height", 40);
//   prog.AddQuadraticCost(z, weights.asDiagonal().toDenseMatrix(), Eigen::VectorXd::Zero(40));
//   const ConstraintRows smooth = prog.AddLinearConstraint({{z, D}}, -slope, slope);
//   ActiveSetQpSolver solver;                    // holds its workspace and factorizations
//   SolveResult result;                          // reused: sized by the first solve
//   Eigen::VectorXd linear(40);                  // sized once
//   for (;;) {                                   // every 3 ms cycle
//     prog.SetVariableBounds(z, z_min, z_max);   // in place, no allocation
//     linear = -weights.cwiseProduct(z_ref);     // evaluate into storage: no temporary
//     prog.SetLinearCost(z, linear);
//     solver.Solve(prog, &result);               // warm-started from the last active set
//     if (result.status != SolveStatus::kSolved) { /* keep the last plan */ }
//     Use(result.x.segment(z.start, z.size));
//   }
//
// Setters check sizes and finiteness and throw std::invalid_argument naming the block or rows.
// Pass plain vectors or segments to the setters: an expression would be evaluated into a
// temporary (an allocation). The Mutable*() accessors are unchecked (for readers that fill whole
// matrices); Solve() checks the data again and reports SolveStatus::kInvalidInput for NaN.
// MutableHessian() and MutableConstraintMatrix() mark the matrix as changed when called, so call
// them again for every change rather than keeping the reference across solves.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

/// The optimisation core: programs, solvers and QP benchmark sets; it includes nothing else of stairplan.
namespace stairplan::optim {

/// Infinity: a bound that does not bind.
constexpr double kInf = std::numeric_limits<double>::infinity();
/// Bounds at or beyond this magnitude mean "no bound" (QPS files use 1e30).
constexpr double kInfiniteBound = 1e20;

/// A contiguous block of decision variables.
struct VariableBlock {
  std::string name;  ///< for messages
  int start = 0;  ///< index of its first variable in x
  int size = 0;  ///< number of variables
  /// This block's values inside the full vector x.
  Eigen::VectorBlock<const Eigen::VectorXd> Of(const Eigen::VectorXd& x) const { return x.segment(start, size); }
};

/// A contiguous group of linear constraint rows.
struct ConstraintRows {
  std::string name;  ///< for messages
  int start = 0;  ///< index of its first row
  int size = 0;  ///< number of rows
};

/// One block's coefficients in a linear constraint: rows x block.size.
using LinearTerm = std::pair<VariableBlock, Eigen::MatrixXd>;

/// A nonlinear cost f(x) depending on some blocks, with its gradient per block.
struct NonlinearCost {
  std::string name;  ///< for messages
  std::vector<VariableBlock> blocks;  ///< the blocks f depends on, in the order `gradient` indexes them
  std::function<double(const Eigen::VectorXd& x)> value;  ///< f(x) over the full vector x
  /// Writes df/d(blocks[block]) into `out` (size blocks[block].size).
  std::function<void(const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::VectorXd> out)> gradient;
  /// Optional: writes d2f/(d blocks[a] d blocks[b]) into `out` (blocks[a].size x blocks[b].size)
  /// for each pair (a, b) of hessian_pairs. Solvers that can use second derivatives (Ipopt) do so
  /// when every nonlinear part of the program has them; otherwise they approximate.
  /// (Default-initialised so that aggregate initialisations written before it stay warning-free.)
  std::function<void(const Eigen::VectorXd& x, int a, int b, Eigen::Ref<Eigen::MatrixXd> out)> hessian = {};
  /// The block pairs (a, b), b <= a, where d2f may be nonzero (the sparsity); empty: every pair.
  std::vector<std::pair<int, int>> hessian_pairs = {};
};

/// Nonlinear constraints lower <= c(x) <= upper, with Jacobians per block.
struct NonlinearConstraint {
  std::string name;  ///< for messages
  std::vector<VariableBlock> blocks;  ///< the blocks c depends on, in the order `jacobian` indexes them
  ///@{
  Eigen::VectorXd lower, upper;  ///< bounds on c(x), one per row; +-inf: none
  ///@}
  /// Writes c(x) into `out` (size lower.size()).
  std::function<void(const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> out)> value;
  /// Writes dc/d(blocks[block]) into `out` (rows x blocks[block].size).
  std::function<void(const Eigen::VectorXd& x, int block, Eigen::Ref<Eigen::MatrixXd> out)> jacobian;
  /// Optional: writes sum_i weights[i] d2c_i/(d blocks[a] d blocks[b]) into `out` (blocks[a].size x
  /// blocks[b].size) for each pair (a, b) of hessian_pairs; weights has one entry per row (the
  /// solver's multipliers). See NonlinearCost::hessian.
  std::function<void(const Eigen::VectorXd& x, const Eigen::Ref<const Eigen::VectorXd>& weights, int a, int b,
                     Eigen::Ref<Eigen::MatrixXd> out)>
      hessian = {};
  /// The block pairs (a, b), b <= a, where some d2c_i may be nonzero; empty: every pair.
  std::vector<std::pair<int, int>> hessian_pairs = {};
};

/// The block pairs a Hessian callback is asked for: `pairs`, or every (a, b) with b <= a when empty.
std::vector<std::pair<int, int>> HessianPairs(const std::vector<std::pair<int, int>>& pairs, int blocks);

/// min 0.5 x'Hx + g'x + constant + sum f_i(x)
/// s.t. row_lower <= A x <= row_upper, lower <= c_j(x) <= upper, var_lower <= x <= var_upper.
class Program {
 public:
  Program() = default;

  // ---- building (may allocate) ----
  /// Adds `size` variables named `name`; they start unbounded with initial guess 0.
  VariableBlock AddVariables(const std::string& name, int size);
  /// Adds 0.5 x_b'Q x_b + g'x_b; Q must be square and symmetric-sized to the block.
  void AddQuadraticCost(const VariableBlock& block, const Eigen::MatrixXd& Q, const Eigen::VectorXd& g);
  /// Adds x_a' Q x_b (a cross term between two blocks; Q is a.size x b.size).
  void AddCrossQuadraticCost(const VariableBlock& a, const VariableBlock& b, const Eigen::MatrixXd& Q);
  /// Adds g'x_b.
  void AddLinearCost(const VariableBlock& block, const Eigen::VectorXd& g);
  /// Adds a constant to the objective.
  void AddConstant(double c) { constant_ += c; }
  /// Adds rows lower <= sum_k A_k x_{b_k} <= upper; equal bounds make equalities, +-inf one side.
  ConstraintRows AddLinearConstraint(const std::vector<LinearTerm>& terms, const Eigen::VectorXd& lower,
                                     const Eigen::VectorXd& upper, const std::string& name = "");
  /// Adds a nonlinear cost (the program is then not quadratic).
  void AddNonlinearCost(NonlinearCost cost);
  /// Adds nonlinear constraint rows (the program is then not quadratic).
  void AddNonlinearConstraint(NonlinearConstraint constraint);
  /// Resizes to n variables in one block "x" and m empty rows (for file readers).
  void ResizeDense(int n, int m);

  // ---- updating in place (no allocation) ----
  /// Replaces the bounds of `block`'s variables (+-inf: none).
  void SetVariableBounds(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& lower,
                         const Eigen::Ref<const Eigen::VectorXd>& upper);
  /// Replaces the linear cost of a block (the part added by AddQuadraticCost/AddLinearCost).
  void SetLinearCost(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& g);
  /// Replaces the bounds of `rows` (+-inf: none).
  void SetConstraintBounds(const ConstraintRows& rows, const Eigen::Ref<const Eigen::VectorXd>& lower,
                           const Eigen::Ref<const Eigen::VectorXd>& upper);
  /// Replaces the coefficients of `block` in `rows`.
  void SetConstraintCoefficients(const ConstraintRows& rows, const VariableBlock& block,
                                 const Eigen::Ref<const Eigen::MatrixXd>& coefficients);
  /// Replaces one coefficient: of variable `index` of `block` in row `row` of `rows` (for the
  /// per-cycle updates of a few entries, where a row block would write every column).
  void SetConstraintCoefficient(const ConstraintRows& rows, int row, const VariableBlock& block, int index,
                                double value);
  /// One coefficient of a row: of the program's variable `column` (a block's start plus the
  /// variable's index in it).
  struct Coefficient {
    int column = 0;      ///< the variable's index in x
    double value = 0.0;  ///< its coefficient in the row
  };
  /// Replaces `count` coefficients of row `row` of `rows` at once, as many SetConstraintCoefficient
  /// calls would (the same tracking for solvers), checked and counted once for the row: the body
  /// planner rewrites a few coefficients of hundreds of rows every cycle.
  void SetRowCoefficients(const ConstraintRows& rows, int row, const Coefficient* coefficients, int count);
  /// Replaces the initial guess of `block`'s variables.
  void SetInitialGuess(const VariableBlock& block, const Eigen::Ref<const Eigen::VectorXd>& x0);

  // ---- unchecked whole-data access (bumps the revision counters; Solve() validates) ----
  Eigen::MatrixXd& MutableHessian();  ///< H, whole
  Eigen::MatrixXd& MutableConstraintMatrix();  ///< A, whole
  Eigen::VectorXd& MutableLinearCost() { return g_; }  ///< g, whole
  Eigen::VectorXd& MutableRowLower() { return row_lower_; }  ///< the row lower bounds, whole
  Eigen::VectorXd& MutableRowUpper() { return row_upper_; }  ///< the row upper bounds, whole
  Eigen::VectorXd& MutableVariableLower() { return var_lower_; }  ///< the variable lower bounds, whole
  Eigen::VectorXd& MutableVariableUpper() { return var_upper_; }  ///< the variable upper bounds, whole
  Eigen::VectorXd& MutableInitialGuess() { return x0_; }  ///< the initial guess, whole
  void SetConstant(double c) { constant_ = c; }  ///< replaces the objective's constant

  // ---- reading ----
  int num_variables() const { return static_cast<int>(g_.size()); }  ///< n: length of x
  int num_rows() const { return static_cast<int>(row_lower_.size()); }  ///< linear constraint rows
  int num_nonlinear_rows() const;  ///< rows of all nonlinear constraints
  const std::vector<VariableBlock>& blocks() const { return blocks_; }  ///< the variable blocks, in order
  const Eigen::MatrixXd& hessian() const { return H_; }  ///< H
  const Eigen::VectorXd& linear_cost() const { return g_; }  ///< g
  double constant() const { return constant_; }  ///< the objective's constant
  const Eigen::MatrixXd& constraint_matrix() const { return A_; }  ///< A
  const Eigen::VectorXd& row_lower() const { return row_lower_; }  ///< lower bounds of A x
  const Eigen::VectorXd& row_upper() const { return row_upper_; }  ///< upper bounds of A x
  const Eigen::VectorXd& variable_lower() const { return var_lower_; }  ///< lower bounds of x
  const Eigen::VectorXd& variable_upper() const { return var_upper_; }  ///< upper bounds of x
  const Eigen::VectorXd& initial_guess() const { return x0_; }  ///< x0, where solvers start
  /// The nonlinear costs f_i.
  const std::vector<NonlinearCost>& nonlinear_costs() const { return nonlinear_costs_; }
  /// The nonlinear constraints c_j.
  const std::vector<NonlinearConstraint>& nonlinear_constraints() const { return nonlinear_constraints_; }
  /// True when there are no nonlinear costs or constraints.
  bool IsQuadratic() const { return nonlinear_costs_.empty() && nonlinear_constraints_.empty(); }
  /// True when every nonlinear cost and constraint has a Hessian callback (quadratic programs too).
  bool HasHessians() const;

  /// Objective value at x (quadratic part, constant and nonlinear costs).
  double Objective(const Eigen::VectorXd& x) const;
  /// Largest violation of rows, nonlinear constraints and variable bounds at x.
  double MaxViolation(const Eigen::VectorXd& x) const;

  /// Changes whenever H (or the problem's size) changes; solvers key cached factorizations on it.
  std::uint64_t hessian_revision() const { return hessian_revision_; }
  /// Changes whenever A (or the problem's size) changes.
  std::uint64_t matrix_revision() const { return matrix_revision_; }
  /// Changes when A changes other than through SetConstraintCoefficients (building, resizing,
  /// MutableConstraintMatrix()): then every row counts as changed.
  std::uint64_t whole_matrix_revision() const { return whole_matrix_revision_; }
  /// The matrix revision at which row k's coefficients last changed (SetConstraintCoefficients
  /// changes only its rows): a solver that saw revision r needs to look again only at rows whose
  /// revision is above r, as long as whole_matrix_revision() is still what it saw.
  std::uint64_t row_revision(int k) const { return row_revision_[static_cast<std::size_t>(k)]; }
  /// Single coefficients tracked per row (SetConstraintCoefficient) before the row counts as
  /// written anywhere.
  static constexpr int kTrackedColumns = 8;
  /// Where row k's coefficients may have changed since matrix revision `seen`: false when
  /// anywhere (the matrix changed as a whole, SetConstraintCoefficients wrote the row, or
  /// SetConstraintCoefficient wrote it at more than kTrackedColumns columns); otherwise true with
  /// the columns, ascending, at which SetConstraintCoefficient wrote it. A reader that knows the
  /// row's nonzeros at `seen` then finds all of today's among those and these, without reading
  /// the row's other coefficients (a column-major A strides by its height along a row).
  bool WrittenColumns(int k, std::uint64_t seen, const int** columns, int* count) const;

 private:
  void CheckBlock(const VariableBlock& block, const char* what) const;
  void CheckRows(const ConstraintRows& rows, const char* what) const;
  void TouchHessian();
  void TouchMatrix();
  // Adds `column` to row k's written columns (ascending; past kTrackedColumns the row counts as
  // written anywhere).
  void TrackWrittenColumn(int k, int column);

  std::vector<VariableBlock> blocks_;
  std::vector<ConstraintRows> row_groups_;
  Eigen::MatrixXd H_;
  Eigen::VectorXd g_;
  double constant_ = 0.0;
  Eigen::MatrixXd A_;
  Eigen::VectorXd row_lower_, row_upper_;
  Eigen::VectorXd var_lower_, var_upper_;
  Eigen::VectorXd x0_;
  std::vector<NonlinearCost> nonlinear_costs_;
  std::vector<NonlinearConstraint> nonlinear_constraints_;
  std::uint64_t hessian_revision_ = 0;
  std::uint64_t matrix_revision_ = 0;
  std::uint64_t whole_matrix_revision_ = 0;
  std::vector<std::uint64_t> row_revision_;  // per row of A
  // Per row of A: the revision at which it was last written other than by single coefficients,
  // and the columns single coefficients were written at since (count kTrackedColumns + 1: more).
  std::vector<std::uint64_t> row_whole_revision_;
  std::vector<std::array<int, kTrackedColumns>> written_columns_;
  std::vector<int> written_count_;
};

/// A bound value with +-1e20 and beyond mapped to +-inf.
inline double NormalizeBound(double b) {
  if (b >= kInfiniteBound) return kInf;
  if (b <= -kInfiniteBound) return -kInf;
  return b;
}

}  // namespace stairplan::optim
