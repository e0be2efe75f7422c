// PackedRows: the nonzeros of a dense matrix by rows (compressed rows), taken whole in one pass
// over its column-major storage; for a symmetric matrix from its lower triangle only.
//
// Why: a cold solve of the banded interior-point solver reads the Program's dense H and A whole
// (the body QP's 120 x 120 and 194 x 120 hold about 1,100 nonzeros among 37,700 entries), and
// that read was a tenth of the solve. Runs of zeros are skipped eight entries at a time by one
// test on their bits (the loop vectorises without target flags), and a symmetric H is read
// below its diagonal only. Storage only grows: taking a matrix of the same size and nonzeros
// again allocates nothing.
//
//   PackedRows a;  a.Assign(program.constraint_matrix());
//   PackedRows h;  h.AssignSymmetric(program.hessian());
//   for (int e = a.RowBegin(k); e < a.RowEnd(k); ++e) use(a.ColumnAt(e), a.ValueAt(e));
#pragma once

#include <vector>

#include <Eigen/Core>

namespace stairplan::optim {

/// Compressed rows of a dense matrix (see the file's top comment).
class PackedRows {
 public:
  /// Takes every nonzero of `a`; each row's columns ascending.
  void Assign(const Eigen::MatrixXd& a);
  /// Takes the nonzeros of the symmetric `a` from its lower triangle (the upper one is not
  /// read), each off-diagonal one in both rows; each row's columns ascending.
  void AssignSymmetric(const Eigen::MatrixXd& a);
  /// Takes the transpose of `a` (its columns as rows): for products A'y by rows (gathers),
  /// where adding y_k a_k row by row stores into the entries the next row reads.
  void AssignTransposeOf(const PackedRows& a);

  int rows() const { return m_; }  ///< rows of the matrix taken
  int cols() const { return n_; }  ///< columns of the matrix taken
  int nonzeros() const { return start_.empty() ? 0 : start_[static_cast<std::size_t>(m_)]; }  ///< stored entries
  ///@{
  /// Row k's nonzeros are the slots [RowBegin(k), RowEnd(k)), with ColumnAt(e) and ValueAt(e).
  int RowBegin(int k) const { return start_[static_cast<std::size_t>(k)]; }
  int RowEnd(int k) const { return start_[static_cast<std::size_t>(k) + 1]; }
  int ColumnAt(int e) const { return column_[static_cast<std::size_t>(e)]; }
  double ValueAt(int e) const { return value_[static_cast<std::size_t>(e)]; }
  ///@}
  /// Row k times x.
  double RowDot(int k, const Eigen::VectorXd& x) const {
    double sum = 0.0;
    for (int e = RowBegin(k); e < RowEnd(k); ++e) sum += ValueAt(e) * x[ColumnAt(e)];
    return sum;
  }
  /// y += alpha a_k (row k, as a column).
  void AddRow(int k, double alpha, Eigen::VectorXd* y) const {
    for (int e = RowBegin(k); e < RowEnd(k); ++e) (*y)[ColumnAt(e)] += alpha * ValueAt(e);
  }
  /// y = M x: the first rows() entries of y (sized by the caller; x may be longer than cols()).
  void Multiply(const Eigen::VectorXd& x, Eigen::VectorXd* y) const;

 private:
  void Take(const Eigen::MatrixXd& a, bool symmetric);
  // The padded copy (see padded_width_), when the rows are short and of similar lengths.
  void Pad();

  int m_ = 0, n_ = 0;
  std::vector<int> start_, column_;
  std::vector<double> value_;
  // Every row padded to padded_width_ entries (0 when there is no padded copy) with zeros at the
  // row's first column (column 0 in an empty row): Multiply() then runs without a loop exit per
  // row, whose misprediction on rows of 2 and 3 entries cost more than their products.
  int padded_width_ = 0;
  std::vector<int> padded_column_;
  std::vector<double> padded_value_;
  // The nonzeros in column order (row, value), and each column's end, before sorting into rows.
  std::vector<int> scratch_row_, scratch_column_end_, cursor_;
  std::vector<double> scratch_value_;
};

}  // namespace stairplan::optim
