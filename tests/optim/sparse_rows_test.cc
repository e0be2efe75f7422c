// SparseRows, the active-set solver's copy of A's nonzeros: its products equal the dense ones,
// and it follows row updates, in place when the new nonzeros fit the row's slots (its nonzeros
// again and four spare) and by a rebuild when they do not, read whole or only at the columns the
// program says were written.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>

#include <Eigen/Core>

#include "stairplan/optim/program.h"
#include "stairplan/optim/sparse_rows.h"

using stairplan::optim::SparseRows;

namespace {

// A 7 x 5 matrix with a free row (row 3), a full row (row 5) and scattered entries.
Eigen::MatrixXd Example() {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(7, 5);
  a(0, 0) = 1.0, a(0, 4) = -2.0;
  a(1, 1) = 3.0;
  a(2, 2) = -1.0, a(2, 3) = 2.0, a(2, 4) = 0.5;
  for (int i = 0; i < 5; ++i) a(5, i) = 1.0 + i;
  a(4, 0) = 4.0;
  a(6, 3) = -3.0;
  return a;
}

// Every product of `rows` against the dense `a`.
void CheckAgainstDense(const SparseRows& rows, const Eigen::MatrixXd& a) {
  Eigen::VectorXd x(5);
  x << 0.3, -1.2, 2.0, 0.7, -0.4;
  Eigen::VectorXd ax(7);
  rows.Multiply(x, &ax);
  CHECK((ax - a * x).lpNorm<Eigen::Infinity>() < 1e-14);
  for (int k = 0; k < 7; ++k) CHECK(rows.RowDot(k, x) == Approx(a.row(k).dot(x)).margin(1e-14));
  const Eigen::VectorXd u = (Eigen::VectorXd(7) << 1.0, 0.0, -2.0, 5.0, 0.5, -1.0, 3.0).finished();
  Eigen::VectorXd aty = Eigen::VectorXd::Constant(5, 1.0);
  rows.AddTransposeMultiply(u, &aty);
  CHECK((aty - (Eigen::VectorXd::Constant(5, 1.0) + a.transpose() * u)).lpNorm<Eigen::Infinity>() < 1e-14);
  Eigen::MatrixXd j(5, 5);
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) j(r, c) = 0.1 * (r + 1) - 0.3 * c + (r == c ? 1.0 : 0.0);
  }
  Eigen::VectorXd d(5);
  for (int k = 0; k < 7; ++k) {
    rows.TransposedTimesRow(j, k, -1.0, &d);
    CHECK((d - (-1.0) * j.transpose() * a.row(k).transpose()).lpNorm<Eigen::Infinity>() < 1e-14);
  }
}

}  // namespace

TEST_CASE("sparse rows multiply as the dense matrix does", "[sparse_rows]") {
  const Eigen::MatrixXd a = Example();
  SparseRows rows;
  rows.Resize(7, 5);
  rows.Assign(a);
  CheckAgainstDense(rows, a);
}

TEST_CASE("a changed row is taken in place when it fits and rebuilt when it does not", "[sparse_rows]") {
  Eigen::MatrixXd a = Example();
  SparseRows rows;
  rows.Resize(7, 5);
  rows.Assign(a);
  REQUIRE(rows.builds() == 1);
  // Fits: row 2 loses one nonzero and changes another.
  a(2, 2) = 0.0;
  a(2, 4) = 7.0;
  rows.UpdateRow(a, 2);
  CheckAgainstDense(rows, a);
  // Fits the spare slots: the free row 3 and row 1 gain nonzeros.
  a(3, 1) = 2.5;
  a(3, 4) = -1.5;
  rows.UpdateRow(a, 3);
  a(1, 0) = -6.0;
  rows.UpdateRow(a, 1);
  CheckAgainstDense(rows, a);
  CHECK(rows.builds() == 1);
  // Row 2 takes back the zeroed entry and fills the row: its slots (min(n, 2 * 3 + 4) = 5) hold
  // all five.
  a(2, 2) = 9.0;
  a(2, 0) = 1.0;
  a(2, 1) = -4.0;
  rows.UpdateRow(a, 2);
  CheckAgainstDense(rows, a);
  CHECK(rows.builds() == 1);
}

TEST_CASE("a row that outgrows its slots rebuilds the copy", "[sparse_rows]") {
  // 12 columns: a row of one nonzero has 2 + 4 = 6 slots, so a seventh nonzero does not fit.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 12);
  a(0, 0) = 1.0;
  a(1, 5) = 2.0;
  a(2, 11) = -1.0;
  SparseRows rows;
  rows.Resize(3, 12);
  rows.Assign(a);
  for (int i = 1; i < 6; ++i) a(1, i) = 0.5 * i;  // row 1: columns 1..5, five nonzeros
  rows.UpdateRow(a, 1);
  CHECK(rows.builds() == 1);
  a(1, 7) = 3.0;
  a(1, 8) = 3.5;  // seven nonzeros
  rows.UpdateRow(a, 1);
  CHECK(rows.builds() == 2);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(12, -1.0, 2.0);
  Eigen::VectorXd ax(3);
  rows.Multiply(x, &ax);
  CHECK((ax - a * x).lpNorm<Eigen::Infinity>() < 1e-14);
}

TEST_CASE("rows read only where the program says they were written follow the dense matrix", "[sparse_rows]") {
  // A consumer as the active-set solver is one: after each batch of writes it looks again only at
  // the rows whose revision moved, at the columns WrittenColumns names (and the nonzeros it knew)
  // where it can, and reads the row whole where it cannot. Random single writes (zeros, new
  // columns, more than kTrackedColumns in a row) and block writes, fixed seed.
  using stairplan::optim::ConstraintRows;
  using stairplan::optim::Program;
  using stairplan::optim::VariableBlock;
  constexpr int kN = 30, kM = 12;
  Program p;
  const VariableBlock x = p.AddVariables("x", kN);
  Eigen::MatrixXd initial = Eigen::MatrixXd::Zero(kM, kN);
  for (int k = 0; k < kM; ++k) initial(k, (3 * k) % kN) = 1.0 + k;
  const Eigen::VectorXd lower = Eigen::VectorXd::Constant(kM, -1.0), upper = -lower;
  const ConstraintRows rows = p.AddLinearConstraint({{x, initial}}, lower, upper, "rows");
  SparseRows copy;
  copy.Resize(kM, kN);
  copy.Assign(p.constraint_matrix());
  std::uint64_t seen = p.matrix_revision();
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> row_of(0, kM - 1), column_of(0, kN - 1), kind(0, 9);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  int partial = 0, whole = 0;
  for (int batch = 0; batch < 300; ++batch) {
    for (int w = 0; w < 6; ++w) {
      const int k = row_of(rng);
      const int roll = kind(rng);
      if (roll == 0) {
        Eigen::MatrixXd block = Eigen::MatrixXd::Zero(1, 4);
        block(0, 0) = value(rng);
        block(0, 2) = value(rng);
        p.SetConstraintCoefficients({"one", k, 1}, {"few", 5, 4}, block);
      } else {
        // Mostly within a few columns per row, sometimes anywhere; a fifth of them zeros.
        const int column = roll < 8 ? (k + 7 * (roll % 3)) % kN : column_of(rng);
        p.SetConstraintCoefficient(rows, k, x, column, roll % 5 == 0 ? 0.0 : value(rng));
      }
    }
    const Eigen::MatrixXd& a = p.constraint_matrix();
    for (int k = 0; k < kM; ++k) {
      if (p.row_revision(k) <= seen) continue;
      const int* columns = nullptr;
      int count = 0;
      if (p.WrittenColumns(k, seen, &columns, &count) && copy.UpdateRowAt(a, k, columns, count)) {
        ++partial;
        for (int i = 1; i < count; ++i) CHECK(columns[i - 1] < columns[i]);
      } else {
        ++whole;
        copy.UpdateRow(a, k);
      }
    }
    seen = p.matrix_revision();
    const Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(kN, -1.0, 2.0);
    for (int k = 0; k < kM; ++k) REQUIRE(copy.RowDot(k, probe) == Approx(a.row(k).dot(probe)).margin(1e-13));
    REQUIRE(copy.RowNorm(0) == Approx(a.row(0).norm()).margin(1e-13));
  }
  // Both ways were taken: rows read at their written columns, and rows read whole.
  CHECK(partial > 100);
  CHECK(whole > 20);
}
