// SparseRows: a compressed-row copy of a Program's dense constraint matrix, for the active-set
// solver's per-iteration products (A x, A' y, one row times a vector).
//
// Why: the programs the solver sees every cycle are structurally sparse (the body QP's 472 x 160
// matrix has about 1,100 nonzeros: two per hip and support row, three per acceleration row), and
// dense products over all of A were most of a warm solve's time. The copy follows the Program's
// row revisions: a changed row whose nonzeros fit in the row's slots is rewritten in place; one
// that does not fit rebuilds the copy. Each row keeps spare slots (as many again as its nonzeros,
// and four): the body planner's rows gain nonzeros when a leg's Jacobian or a support pair's
// edge changes, and rebuilding the whole copy for one such row was a seventh of a leg-row
// plan's time. Storage for a dense matrix is reserved when the size is set, so neither
// allocates.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace stairplan::optim {

/// A compressed-row copy of a Program's dense constraint matrix, following its row revisions.
class SparseRows {
 public:
  /// Reserves storage for an m x n matrix (allocates; once per size).
  void Resize(int m, int n);
  /// Copies the nonzeros of `a` (m x n as sized).
  void Assign(const Eigen::MatrixXd& a);
  /// Copies the nonzeros of `a` (any size) without spare slots, reading it column by column: for
  /// readers that take the whole matrix again whenever it changes (a cold solve reads it once,
  /// where Resize's m x n storage and Assign's strided reads cost more than the solve's
  /// iterations). Allocates only to grow. UpdateRow and UpdateRowAt need Resize and Assign.
  void AssignPacked(const Eigen::MatrixXd& a);
  /// Takes row k of `a` again, in place when its nonzeros fit the row's slots; rebuilds the copy
  /// from `a` when they do not.
  void UpdateRow(const Eigen::MatrixXd& a, int k);
  /// Takes row k of `a` again where it can have nonzeros: the row's present ones and `columns`
  /// (`count` of them, ascending; Program::WrittenColumns). False, with the row untouched, when
  /// they are too many to merge here (then UpdateRow()).
  bool UpdateRowAt(const Eigen::MatrixXd& a, int k, const int* columns, int count);

  /// Times the copy was built (Assign, and rows that outgrew their slots).
  int builds() const { return builds_; }
  /// The Euclidean norm of row k.
  double RowNorm(int k) const;
  /// Number of rows m.
  int rows() const { return m_; }
  ///@{
  /// Row k's nonzeros are the slots [RowBegin(k), RowEnd(k)), with ColumnAt(e) and ValueAt(e):
  /// for readers that need the pattern itself (a factorisation's assembly).
  int RowBegin(int k) const { return start_[static_cast<std::size_t>(k)]; }
  int RowEnd(int k) const { return end_[static_cast<std::size_t>(k)]; }
  int ColumnAt(int e) const { return column_[static_cast<std::size_t>(e)]; }
  double ValueAt(int e) const { return value_[static_cast<std::size_t>(e)]; }
  ///@}
  /// Row k times x.
  double RowDot(int k, const Eigen::VectorXd& x) const {
    double sum = 0.0;
    for (int e = start_[static_cast<std::size_t>(k)]; e < end_[static_cast<std::size_t>(k)]; ++e) {
      sum += value_[static_cast<std::size_t>(e)] * x[column_[static_cast<std::size_t>(e)]];
    }
    return sum;
  }
  /// y += alpha a_k (row k of A, as a column).
  void AddRow(int k, double alpha, Eigen::VectorXd* y) const {
    for (int e = start_[static_cast<std::size_t>(k)]; e < end_[static_cast<std::size_t>(k)]; ++e) {
      (*y)[column_[static_cast<std::size_t>(e)]] += alpha * value_[static_cast<std::size_t>(e)];
    }
  }
  /// y = A x.
  void Multiply(const Eigen::VectorXd& x, Eigen::VectorXd* y) const;
  /// y += A' u.
  void AddTransposeMultiply(const Eigen::VectorXd& u, Eigen::VectorXd* y) const;
  /// d = sigma J' a_k for the row a_k of A (J square, column-major: reads the rows of J that
  /// row k touches).
  void TransposedTimesRow(const Eigen::MatrixXd& j, int k, double sigma, Eigen::VectorXd* d) const;

 private:
  // Writes row k's nonzeros from its first slot on, before slot `limit`; false when they do not
  // fit (the row is then partly written).
  bool FillRow(const Eigen::MatrixXd& a, int k, int limit);

  int m_ = 0, n_ = 0;
  int builds_ = 0;
  std::vector<int> start_;   // m + 1 offsets into column_ and value_: row k's slots
  std::vector<int> end_;     // m: the end of row k's nonzeros (start_[k + 1] at most)
  std::vector<int> column_;  // capacity m * n
  std::vector<double> value_;
  // AssignPacked's column-ordered nonzeros before they are sorted into rows.
  std::vector<int> scratch_row_, scratch_column_end_;
  std::vector<double> scratch_value_;
};

}  // namespace stairplan::optim
