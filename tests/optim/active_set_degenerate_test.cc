// ActiveSetQpSolver on degenerate working sets: duplicate and parallel rows active together, and
// warm starts from stale active sets (bounds moved so the old working set is inconsistent or
// infeasible as equalities). Every solve must agree with a cold solve of the same QP.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "stairplan/optim/active_set_qp_solver.h"
#include "test_paths.h"

using namespace stairplan::optim;

namespace {

// A strictly convex QP whose rows come in copies: each base row appears `copies` times, scaled
// by random positive factors (parallel) or exactly (duplicates), with bounds that coincide or
// differ a little, so several copies are active together at the optimum.
struct DegenerateQp {
  Program program;
  VariableBlock x;
  ConstraintRows rows;
  Eigen::VectorXd row_lo, row_hi, var_lo, var_hi, g;
};

DegenerateQp MakeDegenerateQp(int n, int base_rows, int copies, bool exact_copies, std::mt19937& rng,
                              double tilt = 0.0) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  DegenerateQp q;
  q.x = q.program.AddVariables("x", n);
  Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(n, n, [&]() { return normal(rng); });
  const Eigen::MatrixXd H = M * M.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n);
  q.g = Eigen::VectorXd::NullaryExpr(n, [&]() { return 5.0 * normal(rng); });
  q.program.AddQuadraticCost(q.x, H, q.g);
  const int m = base_rows * copies;
  Eigen::MatrixXd A(m, n);
  q.row_lo.resize(m);
  q.row_hi.resize(m);
  for (int b = 0; b < base_rows; ++b) {
    const Eigen::RowVectorXd a = Eigen::RowVectorXd::NullaryExpr(n, [&]() { return normal(rng); });
    const double lo = -0.3 - uniform(rng), hi = 0.3 + uniform(rng);
    for (int c = 0; c < copies; ++c) {
      const double scale = exact_copies ? 1.0 : 0.5 + uniform(rng);
      A.row(b * copies + c) = scale * a;
      if (c > 0 && tilt > 0.0) A(b * copies + c, c % n) += tilt * normal(rng);
      // Same bounds, or one copy a hair tighter (both end up active within the tolerance).
      const double shift = (c == 1 && uniform(rng) < 0.3) ? (tilt > 0.0 ? 1e-3 : 1e-12) : 0.0;
      q.row_lo[b * copies + c] = scale * (lo + shift);
      q.row_hi[b * copies + c] = scale * (hi - shift);
    }
  }
  q.rows = q.program.AddLinearConstraint({{q.x, A}}, q.row_lo, q.row_hi, "rows");
  q.var_lo = Eigen::VectorXd::Constant(n, -2.0);
  q.var_hi = Eigen::VectorXd::Constant(n, 2.0);
  q.program.SetVariableBounds(q.x, q.var_lo, q.var_hi);
  return q;
}

// Solves `program` cold with a fresh solver.
SolveResult ColdSolve(const Program& program) {
  ActiveSetQpSolver cold;
  cold.settings().warm_start = false;
  return cold.Solve(program);
}

void CheckSame(const SolveResult& warm, const SolveResult& cold, const Program& program) {
  REQUIRE(cold.status == SolveStatus::kSolved);
  INFO("warm status " << ToString(warm.status) << ", iterations " << warm.info.iterations);
  REQUIRE(warm.status == SolveStatus::kSolved);
  REQUIRE(warm.x.allFinite());
  CHECK(program.MaxViolation(warm.x) < 1e-7);
  CHECK(std::abs(warm.objective - cold.objective) < 1e-7 * (1.0 + std::abs(cold.objective)));
  CHECK(warm.info.dual_residual < 1e-6);
}

}  // namespace

TEST_CASE("duplicate rows active together solve to the cold optimum, hot and warm", "[active_set][degenerate]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    const bool exact = trial % 2 == 0;
    DegenerateQp q = MakeDegenerateQp(12, 10, 3, exact, rng);
    ActiveSetQpSolver solver;
    SolveResult result;
    solver.Solve(q.program, &result);
    CheckSame(result, ColdSolve(q.program), q.program);
    // Hot re-solves: the rows' bounds move (all copies together, or one copy alone).
    std::uniform_real_distribution<double> uniform(-0.3, 0.3);
    for (int cycle = 0; cycle < 20; ++cycle) {
      Eigen::VectorXd lo = q.row_lo, hi = q.row_hi;
      for (int k = 0; k < lo.size(); ++k) {
        const double s = uniform(rng);
        lo[k] += s * std::abs(q.row_lo[k]);
        hi[k] += s * std::abs(q.row_hi[k]);
      }
      q.program.SetConstraintBounds(q.rows, lo, hi);
      solver.Solve(q.program, &result);
      CheckSame(result, ColdSolve(q.program), q.program);
    }
  }
}

TEST_CASE("equal lower and upper rows duplicated (equalities) stay consistent", "[active_set][degenerate]") {
  // x0 + x1 = 1 twice, and 2 x0 + 2 x1 = 2: one equality in three rows.
  Program p;
  const VariableBlock x = p.AddVariables("x", 3);
  p.AddQuadraticCost(x, Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1.0, 0.5, 0.0));
  Eigen::MatrixXd A(4, 3);
  A << 1, 1, 0, 1, 1, 0, 2, 2, 0, 0, 1, 1;
  const ConstraintRows rows = p.AddLinearConstraint({{x, A}}, Eigen::Vector4d(1, 1, 2, -kInf),
                                                    Eigen::Vector4d(1, 1, 2, 0.2), "rows");
  ActiveSetQpSolver solver;
  SolveResult r = solver.Solve(p);
  CheckSame(r, ColdSolve(p), p);
  // The equalities turn into inequalities that now pull the other way.
  p.SetConstraintBounds(rows, Eigen::Vector4d(-kInf, 1.2, 2.4, -kInf), Eigen::Vector4d(1.5, kInf, kInf, 0.2));
  solver.Solve(p, &r);
  CheckSame(r, ColdSolve(p), p);
}

TEST_CASE("a stale warm start whose working set is now inconsistent still solves", "[active_set][degenerate]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 60; ++trial) {
    DegenerateQp q = MakeDegenerateQp(10, 12, 2, trial % 3 == 0, rng);
    ActiveSetQpSolver solver;
    SolveResult first = solver.Solve(q.program);
    REQUIRE(first.status == SolveStatus::kSolved);
    // Move every bound a lot: the old active set, taken as equalities, is now far from the
    // optimum (and may put x outside its variable bounds).
    Eigen::VectorXd lo = q.row_lo, hi = q.row_hi;
    for (int k = 0; k < lo.size(); ++k) {
      const double s = normal(rng);
      lo[k] = std::min(lo[k] + s, 0.0);
      hi[k] = std::max(hi[k] + s, lo[k] + 0.05);
    }
    Eigen::VectorXd vlo = q.var_lo + 1.5 * Eigen::VectorXd::Random(10).cwiseAbs();
    Eigen::VectorXd vhi = vlo + Eigen::VectorXd::Constant(10, 0.4);
    q.program.SetConstraintBounds(q.rows, lo, hi);
    q.program.SetVariableBounds(q.x, vlo, vhi);
    const SolveResult cold = ColdSolve(q.program);
    if (cold.status != SolveStatus::kSolved) continue;  // genuinely infeasible: nothing to compare
    // Hot (kept factorisation) and warm (given active set, refactorised).
    SolveResult hot = solver.Solve(q.program);
    CheckSame(hot, cold, q.program);
    ActiveSetQpSolver warm;
    warm.SetWarmStart(first.active_set);
    CheckSame(warm.Solve(q.program), cold, q.program);
  }
}

TEST_CASE("nearly parallel rows with different bounds (two legs' hip rows) match the cold optimum", "[active_set][degenerate]") {
  // The body QP's hip rows z + c_l pitch for two legs whose c differ by roundoff: both cannot be
  // active unless pitch runs to (b1 - b2) / (c1 - c2).
  for (double delta : {0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3}) {
    for (double gap : {0.0, 1e-9, 1e-4, 1e-2}) {
      Program p;
      const VariableBlock x = p.AddVariables("x", 2);  // z, pitch
      p.AddQuadraticCost(x, Eigen::Vector2d(2.0, 2.0).asDiagonal().toDenseMatrix(), Eigen::Vector2d(-1.0, 0.0));
      Eigen::MatrixXd A(3, 2);
      A << 1.0, -0.3, 1.0, -0.3 + delta, 1.0, 0.3;
      p.AddLinearConstraint({{x, A}}, Eigen::Vector3d(-kInf, -kInf, -kInf), Eigen::Vector3d(0.2, 0.2 + gap, 0.5), "hip");
      p.SetVariableBounds(x, Eigen::Vector2d(-kInf, -0.8), Eigen::Vector2d(kInf, 0.8));
      INFO("delta " << delta << " gap " << gap);
      const SolveResult cold = ColdSolve(p);
      REQUIRE(cold.status == SolveStatus::kSolved);
      CHECK(cold.x.allFinite());
      CHECK(p.MaxViolation(cold.x) < 1e-9);
      ActiveSetQpSolver solver;
      SolveResult r = solver.Solve(p);
      CheckSame(r, cold, p);
    }
  }
}

TEST_CASE("nearly parallel copies (tilted by roundoff to 1e-5) with different bounds, hot re-solves", "[active_set][degenerate]") {
  std::mt19937 rng(3);
  int trial = 0;
  for (double tilt : {1e-14, 1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5}) {
    for (int rep = 0; rep < 10; ++rep, ++trial) {
      DegenerateQp q = MakeDegenerateQp(8, 8, 3, false, rng, tilt);
      INFO("tilt " << tilt << " rep " << rep);
      ActiveSetQpSolver solver;
      SolveResult result;
      solver.Solve(q.program, &result);
      CheckSame(result, ColdSolve(q.program), q.program);
      std::uniform_real_distribution<double> uniform(-0.3, 0.3);
      for (int cycle = 0; cycle < 10; ++cycle) {
        Eigen::VectorXd lo = q.row_lo, hi = q.row_hi;
        for (int k = 0; k < lo.size(); ++k) {
          lo[k] += uniform(rng) * std::abs(q.row_lo[k]);
          hi[k] += uniform(rng) * std::abs(q.row_hi[k]);
        }
        q.program.SetConstraintBounds(q.rows, lo, hi);
        solver.Solve(q.program, &result);
        CheckSame(result, ColdSolve(q.program), q.program);
      }
    }
  }
}

TEST_CASE("a warm Infeasible is re-checked from cold before it is reported", "[active_set][degenerate]") {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  p.AddQuadraticCost(x, Eigen::Matrix2d::Identity(), Eigen::Vector2d(-1.0, -1.0));
  Eigen::MatrixXd A(2, 2);
  A << 1.0, 1.0, 1.0, -1.0;
  const ConstraintRows rows = p.AddLinearConstraint({{x, A}}, Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(1.0, 0.5));
  ActiveSetQpSolver solver;
  SolveResult r = solver.Solve(p);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(r.info.cold_restarts == 0);
  p.SetVariableBounds(x, Eigen::Vector2d(2.0, 2.0), Eigen::Vector2d(3.0, 3.0));  // x0 + x1 <= 1: impossible
  solver.Solve(p, &r);
  CHECK(r.status == SolveStatus::kInfeasible);
  CHECK(r.info.cold_restarts == 1);
  p.SetVariableBounds(x, Eigen::Vector2d(-3.0, -3.0), Eigen::Vector2d(3.0, 3.0));
  solver.Solve(p, &r);
  CheckSame(r, ColdSolve(p), p);
  CHECK(r.info.cold_restarts == 0);
}

namespace {

double ReadNumber(std::istream& in) {  // strtod, which reads "inf" and "-inf" as well
  std::string text;
  in >> text;
  return std::strtod(text.c_str(), nullptr);
}

// A QP with a warm start, as tests/optim/data/*.txt keep them: "n m", then lines "H i j v",
// "A i j v" (nonzeros), "g i v", "x i lower upper guess", "r i lower upper" and the warm start's
// active sides "wr row side", "wb variable side".
Program ReadQpWithWarmStart(const std::string& path, ActiveSet* warm) {
  std::ifstream in(path);
  REQUIRE(in.good());
  int n = 0, m = 0;
  in >> n >> m;
  Program p;
  p.ResizeDense(n, m);
  warm->rows.assign(static_cast<std::size_t>(m), 0);
  warm->bounds.assign(static_cast<std::size_t>(n), 0);
  std::string tag;
  int i = 0, j = 0;
  while (in >> tag >> i) {
    if (tag == "H" || tag == "A") {
      in >> j;
      (tag == "H" ? p.MutableHessian() : p.MutableConstraintMatrix())(i, j) = ReadNumber(in);
    } else if (tag == "g") {
      p.MutableLinearCost()[i] = ReadNumber(in);
    } else if (tag == "x") {
      p.MutableVariableLower()[i] = ReadNumber(in);
      p.MutableVariableUpper()[i] = ReadNumber(in);
      p.MutableInitialGuess()[i] = ReadNumber(in);
    } else if (tag == "r") {
      p.MutableRowLower()[i] = ReadNumber(in);
      p.MutableRowUpper()[i] = ReadNumber(in);
    } else {
      in >> j;
      (tag == "wr" ? warm->rows : warm->bounds)[static_cast<std::size_t>(i)] = static_cast<ActiveSide>(j);
    }
  }
  return p;
}

}  // namespace

TEST_CASE("a warm solve that ends outside its bounds is not Solved: it is re-solved from cold", "[active_set][degenerate]") {
  // A cycle of the leg-row body QP (ANYmal B descending, acceleration_weight 1: 319 variables,
  // 1,594 rows) with the working set of the cycle before. From it the closed-form re-solves hit a
  // nearly dependent set, dropped over a hundred constraints at once and ended "solved" 4.9e4
  // outside the bounds, below the true optimum.
  ActiveSet warm;
  const Program p = ReadQpWithWarmStart(stairplan::testing::SourceDir() + "/tests/optim/data/body_qp_warm_breakdown.txt", &warm);
  const SolveResult cold = ColdSolve(p);
  REQUIRE(cold.status == SolveStatus::kSolved);
  ActiveSetQpSolver solver;
  solver.SetWarmStart(warm);
  SolveResult r;
  solver.Solve(p, &r);
  REQUIRE(r.status == SolveStatus::kSolved);
  CHECK(p.MaxViolation(r.x) < 1e-6);
  CHECK(r.objective == Approx(cold.objective).epsilon(1e-9));
  CHECK(r.info.cold_restarts == 1);
}
