// Program: block layout, cost and constraint assembly, in-place updates and their checks.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "stairplan/optim/program.h"

using namespace stairplan::optim;

namespace {

std::string ThrownMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

}  // namespace

TEST_CASE("blocks are laid out one after the other", "[program]") {
  Program p;
  const VariableBlock a = p.AddVariables("a", 2);
  const VariableBlock b = p.AddVariables("b", 3);
  CHECK(a.start == 0);
  CHECK(b.start == 2);
  CHECK(p.num_variables() == 5);
  CHECK(p.variable_lower()[4] == -kInf);
  CHECK(p.variable_upper()[0] == kInf);
}

TEST_CASE("costs and constraints assemble into H, g, A", "[program]") {
  Program p;
  const VariableBlock a = p.AddVariables("a", 2);
  const VariableBlock b = p.AddVariables("b", 1);
  Eigen::MatrixXd Q(2, 2);
  Q << 2, 1, 0, 4;  // not symmetric: the symmetric part is stored
  p.AddQuadraticCost(a, Q, Eigen::Vector2d(1, -1));
  p.AddCrossQuadraticCost(a, b, Eigen::MatrixXd(Eigen::Vector2d(0.5, 0)));
  p.AddLinearCost(b, Eigen::VectorXd::Constant(1, 3.0));
  p.AddConstant(7.0);
  const ConstraintRows rows = p.AddLinearConstraint({{a, Eigen::RowVector2d(1, 1)}, {b, Eigen::MatrixXd::Constant(1, 1, -1)}},
                                                    Eigen::VectorXd::Constant(1, -1e30), Eigen::VectorXd::Constant(1, 2.0), "sum");
  CHECK(rows.start == 0);
  CHECK(p.hessian()(0, 1) == Approx(0.5));
  CHECK(p.hessian()(1, 0) == Approx(0.5));
  CHECK(p.hessian()(0, 2) == Approx(0.5));
  CHECK(p.hessian()(2, 0) == Approx(0.5));
  CHECK(p.row_lower()[0] == -kInf);  // 1e30 means no bound
  const Eigen::Vector3d x(1, 2, 3);
  // 0.5 x'Hx + g'x + c with H = [[2, .5, .5], [.5, 4, 0], [.5, 0, 0]], g = (1, -1, 3).
  const double expected = 0.5 * (2 * 1 + 4 * 4 + 2 * 0.5 * 1 * 2 + 2 * 0.5 * 1 * 3) + (1 - 2 + 9) + 7;
  CHECK(p.Objective(x) == Approx(expected));
  CHECK(p.MaxViolation(x) == Approx(0.0));  // 1 + 2 - 3 = 0 <= 2
  CHECK(p.MaxViolation(Eigen::Vector3d(5, 0, 0)) == Approx(3.0));
}

TEST_CASE("in-place updates change the data and keep the matrices' revisions", "[program]") {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  const ConstraintRows r = p.AddLinearConstraint({{x, Eigen::RowVector2d(1, 1)}}, Eigen::VectorXd::Zero(1),
                                                 Eigen::VectorXd::Ones(1), "r");
  const auto h = p.hessian_revision();
  const auto a = p.matrix_revision();
  p.SetVariableBounds(x, Eigen::Vector2d(-1, -2), Eigen::Vector2d(1, 2));
  p.SetLinearCost(x, Eigen::Vector2d(3, 4));
  p.SetConstraintBounds(r, Eigen::VectorXd::Constant(1, -5), Eigen::VectorXd::Constant(1, 5));
  p.SetInitialGuess(x, Eigen::Vector2d(0.5, 0.5));
  CHECK(p.hessian_revision() == h);
  CHECK(p.matrix_revision() == a);
  CHECK(p.variable_lower()[1] == -2);
  CHECK(p.linear_cost()[1] == 4);
  CHECK(p.row_upper()[0] == 5);
  CHECK(p.initial_guess()[0] == 0.5);
  p.SetConstraintCoefficients(r, x, Eigen::RowVector2d(2, 0));
  CHECK(p.matrix_revision() != a);
  CHECK(p.constraint_matrix()(0, 0) == 2);
}

TEST_CASE("one coefficient changes its row alone", "[program]") {
  Program p;
  const VariableBlock x = p.AddVariables("x", 3);
  const Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  const ConstraintRows r = p.AddLinearConstraint({{x, a}}, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), "r");
  const auto whole = p.whole_matrix_revision();
  const auto before = p.matrix_revision();
  p.SetConstraintCoefficient(r, 1, x, 2, -4.0);
  CHECK(p.constraint_matrix()(1, 2) == -4.0);
  CHECK(p.constraint_matrix().row(1).sum() == -3.0);  // the row's other entries kept
  CHECK(p.whole_matrix_revision() == whole);
  CHECK(p.row_revision(1) > before);
  CHECK(p.row_revision(0) <= before);
  CHECK(p.row_revision(2) <= before);
  CHECK_THAT(ThrownMessage([&] { p.SetConstraintCoefficient(r, 3, x, 0, 1.0); }), Catch::Contains("'r'"));
  CHECK_THAT(ThrownMessage([&] { p.SetConstraintCoefficient(r, 0, x, -1, 1.0); }), Catch::Contains("'x'"));
  CHECK_THAT(ThrownMessage([&] { p.SetConstraintCoefficient(r, 0, x, 0, std::nan("")); }), Catch::Contains("finite"));
}

TEST_CASE("a row's coefficients written at once are as written one by one", "[program]") {
  // Two programs, the same random writes: one coefficient at a time, or each row's at once. The
  // matrices, the rows counted as changed and the columns solvers are told of must agree.
  constexpr int kN = 12, kM = 5;
  Program one, batched;
  std::vector<VariableBlock> blocks;
  std::vector<ConstraintRows> rows;
  for (Program* p : {&one, &batched}) {
    blocks.push_back(p->AddVariables("x", kN));
    rows.push_back(p->AddLinearConstraint({{blocks.back(), Eigen::MatrixXd::Identity(kM, kN)}}, Eigen::VectorXd::Zero(kM),
                                          Eigen::VectorXd::Ones(kM), "r"));
  }
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> row_of(0, kM - 1), column_of(0, kN - 1), count_of(0, 10);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int round = 0; round < 200; ++round) {
    const auto seen_one = one.matrix_revision(), seen_batched = batched.matrix_revision();
    const int row = row_of(rng);
    std::vector<Program::Coefficient> coefficients(static_cast<std::size_t>(count_of(rng)));
    for (Program::Coefficient& c : coefficients) c = {column_of(rng), value(rng)};
    for (const Program::Coefficient& c : coefficients) one.SetConstraintCoefficient(rows[0], row, blocks[0], c.column, c.value);
    batched.SetRowCoefficients(rows[1], row, coefficients.data(), static_cast<int>(coefficients.size()));
    REQUIRE(batched.constraint_matrix() == one.constraint_matrix());
    for (int k = 0; k < kM; ++k) {
      REQUIRE((one.row_revision(k) > seen_one) == (batched.row_revision(k) > seen_batched));
      const int *columns_one = nullptr, *columns_batched = nullptr;
      int count_one = 0, count_batched = 0;
      const bool tracked = one.WrittenColumns(k, seen_one, &columns_one, &count_one);
      REQUIRE(batched.WrittenColumns(k, seen_batched, &columns_batched, &count_batched) == tracked);
      if (!tracked) continue;
      REQUIRE(std::vector<int>(columns_batched, columns_batched + count_batched) ==
              std::vector<int>(columns_one, columns_one + count_one));
    }
  }
  const Program::Coefficient outside{kN, 1.0}, not_finite{0, std::nan("")};
  CHECK_THAT(ThrownMessage([&] { batched.SetRowCoefficients(rows[1], kM, &outside, 0); }), Catch::Contains("'r'"));
  CHECK_THAT(ThrownMessage([&] { batched.SetRowCoefficients(rows[1], 0, &outside, 1); }), Catch::Contains("outside"));
  CHECK_THAT(ThrownMessage([&] { batched.SetRowCoefficients(rows[1], 0, &not_finite, 1); }), Catch::Contains("finite"));
}

TEST_CASE("misuse throws invalid_argument naming the block or rows", "[program]") {
  Program p;
  const VariableBlock x = p.AddVariables("feet", 2);
  const ConstraintRows r = p.AddLinearConstraint({{x, Eigen::RowVector2d(1, 1)}}, Eigen::VectorXd::Zero(1),
                                                 Eigen::VectorXd::Ones(1), "support");
  CHECK_THAT(ThrownMessage([&] { p.SetVariableBounds(x, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3)); }),
             Catch::Contains("feet"));
  CHECK_THAT(ThrownMessage([&] { p.SetLinearCost(x, Eigen::Vector2d(std::nan(""), 0)); }), Catch::Contains("feet"));
  CHECK_THAT(ThrownMessage([&] { p.SetConstraintBounds(r, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1)); }),
             Catch::Contains("support"));
  CHECK_THAT(ThrownMessage([&] { p.AddQuadraticCost(x, Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Zero(3)); }),
             Catch::Contains("feet"));
  const VariableBlock stranger{"stranger", 5, 2};
  CHECK_THAT(ThrownMessage([&] { p.SetInitialGuess(stranger, Eigen::Vector2d::Zero()); }), Catch::Contains("stranger"));
  CHECK_THAT(ThrownMessage([&] { p.AddVariables("empty", 0); }), Catch::Contains("empty"));
}

TEST_CASE("Hessian callbacks are optional and their block pairs are checked", "[program]") {
  Program p;
  const VariableBlock x = p.AddVariables("x", 2);
  CHECK(p.HasHessians());  // nothing nonlinear
  NonlinearCost cost{"bowl", {x}, [](const Eigen::VectorXd& v) { return v.squaredNorm(); },
                     [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::VectorXd> g) { g = 2 * v; }};
  cost.hessian_pairs = {{0, 0}};
  CHECK_THAT(ThrownMessage([&] { p.AddNonlinearCost(cost); }), Catch::Contains("bowl") && Catch::Contains("without"));
  cost.hessian = [](const Eigen::VectorXd&, int, int, Eigen::Ref<Eigen::MatrixXd> h) { h = 2 * Eigen::Matrix2d::Identity(); };
  cost.hessian_pairs = {{0, 1}};  // upper triangle and beyond the cost's one block
  CHECK_THAT(ThrownMessage([&] { p.AddNonlinearCost(cost); }), Catch::Contains("bowl"));
  cost.hessian_pairs = {};
  p.AddNonlinearCost(cost);
  CHECK(p.HasHessians());
  NonlinearConstraint c;
  c.name = "ring";
  c.blocks = {x};
  c.lower = Eigen::VectorXd::Ones(1);
  c.upper = Eigen::VectorXd::Constant(1, kInf);
  c.value = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::VectorXd> out) { out[0] = v.squaredNorm(); };
  c.jacobian = [](const Eigen::VectorXd& v, int, Eigen::Ref<Eigen::MatrixXd> J) { J = 2 * v.transpose(); };
  c.hessian_pairs = {{1, 0}};
  CHECK_THAT(ThrownMessage([&] { p.AddNonlinearConstraint(c); }), Catch::Contains("ring"));
  c.hessian_pairs = {};
  p.AddNonlinearConstraint(c);
  CHECK_FALSE(p.HasHessians());  // the constraint has none
  CHECK(HessianPairs({}, 3).size() == 6);
  CHECK(HessianPairs({{2, 1}}, 3) == std::vector<std::pair<int, int>>{{2, 1}});
}
