// BandCholesky against Eigen's dense Cholesky on random banded SPD matrices, over the bands with
// compiled kernels (1..8), a wider one (run-time band), bands as wide as the matrix, matrices
// shorter than their band; a singular direction's pivot replaced; refactorising after a resize.
#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "stairplan/optim/band_cholesky.h"

using stairplan::optim::BandCholesky;

namespace {

// A random SPD matrix with half-bandwidth b: B B' + shift I with B lower-banded.
Eigen::MatrixXd RandomBand(int n, int b, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = j; i < n && i - j <= b / 2; ++i) l(i, j) = normal(*rng);
  }
  Eigen::MatrixXd a = l * l.transpose();
  for (int j = 0; j < n; ++j) {
    for (int i = j + 1; i < n && i - j <= b; ++i) a(i, j) = a(j, i) = 0.3 * normal(*rng);
  }
  a += (1.0 + 0.5 * b) * Eigen::MatrixXd::Identity(n, n);  // diagonally dominant: SPD
  return a;
}

void Load(const Eigen::MatrixXd& a, int b, BandCholesky* k) {
  k->Resize(static_cast<int>(a.rows()), b);
  k->SetZero();
  for (int j = 0; j < a.cols(); ++j) {
    for (int i = j; i < a.rows() && i - j <= k->bandwidth(); ++i) k->Add(i, j, a(i, j));
  }
}

}  // namespace

TEST_CASE("BandCholesky: solves banded SPD systems as the dense Cholesky does", "[banded-ipm][band]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  BandCholesky k;  // one object throughout: sizes grow and shrink between factorisations
  for (const int n : {1, 2, 3, 5, 9, 40, 121}) {
    for (const int b : {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 200}) {
      INFO("n " << n << " b " << b);
      const Eigen::MatrixXd a = RandomBand(n, std::min(b, n - 1), &rng);
      Load(a, b, &k);
      CHECK(k.bandwidth() == std::min(b, n - 1));
      CHECK(k.Factorize(1e-18) == 0);
      Eigen::VectorXd rhs(n);
      for (int i = 0; i < n; ++i) rhs[i] = normal(rng);
      Eigen::VectorXd x = rhs;
      k.Solve(x.data());
      const Eigen::VectorXd expected = a.llt().solve(rhs);
      CHECK((x - expected).lpNorm<Eigen::Infinity>() <= 1e-10 * (1.0 + expected.lpNorm<Eigen::Infinity>()));
      CHECK((a * x - rhs).lpNorm<Eigen::Infinity>() <= 1e-10 * (1.0 + rhs.lpNorm<Eigen::Infinity>()));
    }
  }
}

TEST_CASE("BandCholesky: a singular direction's pivot is replaced and its component comes out zero",
          "[banded-ipm][band]") {
  std::mt19937 rng(3);
  for (const int b : {2, 4, 11}) {
    const int n = 30, dead = 17;
    Eigen::MatrixXd a = RandomBand(n, b, &rng);
    a.row(dead).setZero();
    a.col(dead).setZero();
    BandCholesky k;
    Load(a, b, &k);
    CHECK(k.Factorize(1e-18) == 1);
    Eigen::VectorXd rhs = Eigen::VectorXd::Ones(n);
    Eigen::VectorXd x = rhs;
    k.Solve(x.data());
    CHECK(std::abs(x[dead]) <= 1e-30);
    // The rest is the solution of the system without the dead variable.
    Eigen::MatrixXd reduced(n - 1, n - 1);
    Eigen::VectorXd reduced_rhs(n - 1), reduced_x(n - 1);
    for (int i = 0, ri = 0; i < n; ++i) {
      if (i == dead) continue;
      reduced_rhs[ri] = rhs[i];
      reduced_x[ri] = x[i];
      for (int j = 0, rj = 0; j < n; ++j) {
        if (j == dead) continue;
        reduced(ri, rj++) = a(i, j);
      }
      ++ri;
    }
    CHECK((reduced_x - reduced.llt().solve(reduced_rhs)).lpNorm<Eigen::Infinity>() <= 1e-10);
  }
}
