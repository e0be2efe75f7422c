// PackedRows against the dense matrices it copies: every nonzero in its row with ascending
// columns, nothing else (signed zeros dropped, NaN kept), products with vectors; a symmetric
// matrix from its lower triangle (the upper one garbage here, to prove it is not read); sizes
// that are and are not multiples of its chunk of eight; taking a second matrix into the same
// object; the transpose of a copy.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Core>

#include "stairplan/optim/packed_rows.h"

using stairplan::optim::PackedRows;

namespace {

// Row by row, the copy's entries are exactly the nonzeros of `a`, columns ascending.
void CheckRows(const PackedRows& p, const Eigen::MatrixXd& a) {
  REQUIRE(p.rows() == a.rows());
  REQUIRE(p.cols() == a.cols());
  int total = 0;
  for (int k = 0; k < a.rows(); ++k) {
    int e = p.RowBegin(k);
    for (int j = 0; j < a.cols(); ++j) {
      if (a(k, j) == 0.0) continue;
      INFO("row " << k << " column " << j);
      REQUIRE(e < p.RowEnd(k));
      CHECK(p.ColumnAt(e) == j);
      CHECK(p.ValueAt(e) == a(k, j));
      ++e;
      ++total;
    }
    CHECK(e == p.RowEnd(k));
  }
  CHECK(p.nonzeros() == total);
}

Eigen::MatrixXd RandomSparse(int m, int n, double density, std::mt19937* rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, n);
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < m; ++k) {
      if (uniform(*rng) < density) a(k, j) = uniform(*rng) - 0.5;
    }
  }
  return a;
}

}  // namespace

TEST_CASE("PackedRows: the nonzeros of a dense matrix by rows", "[banded-ipm][packed-rows]") {
  std::mt19937 rng(11);
  PackedRows p;
  for (const int m : {1, 7, 8, 9, 31, 194}) {
    for (const int n : {1, 5, 120}) {
      for (const double density : {0.0, 0.02, 0.3, 1.0}) {
        INFO("m " << m << " n " << n << " density " << density);
        Eigen::MatrixXd a = RandomSparse(m, n, density, &rng);
        a(m / 2, n / 2) = -0.0;  // a signed zero is a zero
        p.Assign(a);
        CheckRows(p, a);
        Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0), y(m), z = Eigen::VectorXd::Zero(n);
        p.Multiply(x, &y);
        CHECK((y - a * x).lpNorm<Eigen::Infinity>() <= 1e-12);
        for (int k = 0; k < m; ++k) p.AddRow(k, 0.5 * k, &z);
        const Eigen::VectorXd weights = Eigen::VectorXd::LinSpaced(m, 0.0, 0.5 * (m - 1));
        CHECK((z - a.transpose() * weights).lpNorm<Eigen::Infinity>() <= 1e-12);
        PackedRows t;
        t.AssignTransposeOf(p);
        CheckRows(t, a.transpose());
      }
    }
  }
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(9, 2);
  nan(8, 1) = std::numeric_limits<double>::quiet_NaN();
  p.Assign(nan);
  REQUIRE(p.nonzeros() == 1);
  CHECK(p.ColumnAt(p.RowBegin(8)) == 1);
  CHECK(std::isnan(p.ValueAt(p.RowBegin(8))));
}

TEST_CASE("PackedRows: a symmetric matrix from its lower triangle, mirrored", "[banded-ipm][packed-rows]") {
  std::mt19937 rng(5);
  PackedRows p;
  for (const int n : {1, 2, 8, 17, 120}) {
    for (const double density : {0.0, 0.05, 0.5, 1.0}) {
      INFO("n " << n << " density " << density);
      Eigen::MatrixXd lower = RandomSparse(n, n, density, &rng).triangularView<Eigen::Lower>();
      Eigen::MatrixXd symmetric = lower + lower.transpose();
      symmetric.diagonal() = lower.diagonal();
      Eigen::MatrixXd read = symmetric;
      read.triangularView<Eigen::StrictlyUpper>().setConstant(7.0);  // never read
      p.AssignSymmetric(read);
      CheckRows(p, symmetric);
      const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0);
      Eigen::VectorXd y(n);
      p.Multiply(x, &y);
      CHECK((y - symmetric * x).lpNorm<Eigen::Infinity>() <= 1e-12);
    }
  }
}
