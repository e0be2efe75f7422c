// The API boundary (issue #9): NaN or inf in an input throws std::invalid_argument naming the
// argument; a badly posed or badly scaled QP returns a status, never a "solved" with garbage.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/crawl_planner.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/optim/program.h"
#include "stairplan/optim/solver.h"
#include "stairplan/solvers/make_solver.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename Call>
std::string ErrorOf(Call call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

// min 0.5 |x|^2 + g'x  s.t.  lower <= x1 + x2 <= upper
struct SmallQp {
  optim::Program program;
  optim::VariableBlock x;
  optim::ConstraintRows row;
  SmallQp() {
    x = program.AddVariables("x", 2);
    program.AddQuadraticCost(x, Eigen::Matrix2d::Identity(), Eigen::Vector2d(1.0, -1.0));
    row = program.AddLinearConstraint({{x, Eigen::RowVector2d(1.0, 1.0)}}, Eigen::VectorXd::Constant(1, 1.0),
                                      Eigen::VectorXd::Constant(1, 2.0), "sum");
  }
};

}  // namespace

TEST_CASE("stairs: NaN or inf in a field throws naming the field", "[hardening][api]") {
  for (const double bad : {kNaN, kInf, -kInf}) {
    StairSpec spec;
    spec.rise = bad;
    CHECK_THAT(ErrorOf([&] { Staircase{spec}; }), Catch::Contains("rise"));
    spec = StairSpec{};
    spec.run = bad;
    CHECK_THAT(ErrorOf([&] { Staircase{spec}; }), Catch::Contains("run"));
    spec = StairSpec{};
    spec.width = bad;
    CHECK_THAT(ErrorOf([&] { Staircase{spec}; }), Catch::Contains("width"));
  }
}

TEST_CASE("program: NaN or inf in updated data throws naming the block or rows", "[hardening][api][optim]") {
  SmallQp qp;
  CHECK_THAT(ErrorOf([&] { qp.program.SetLinearCost(qp.x, Eigen::Vector2d(kNaN, 0.0)); }), Catch::Contains("'x'"));
  CHECK_THAT(ErrorOf([&] { qp.program.SetLinearCost(qp.x, Eigen::Vector2d(kInf, 0.0)); }), Catch::Contains("'x'"));
  CHECK_THAT(ErrorOf([&] { qp.program.SetInitialGuess(qp.x, Eigen::Vector2d(0.0, -kInf)); }), Catch::Contains("'x'"));
  CHECK_THAT(ErrorOf([&] { qp.program.SetConstraintBounds(qp.row, Eigen::VectorXd::Constant(1, kNaN), Eigen::VectorXd::Constant(1, 1.0)); }),
             Catch::Contains("'sum'"));
  CHECK_THAT(ErrorOf([&] { qp.program.SetConstraintCoefficients(qp.row, qp.x, Eigen::RowVector2d(1.0, kInf)); }),
             Catch::Contains("'sum'"));
}

TEST_CASE("solver: a bound no value meets is invalid input, not solved", "[hardening][api][optim]") {
  // Found by the bad-input table: "x1 + x2 >= 1e400" in a QPS file was reported solved at x = 0.
  for (const auto& [lower, upper] : {std::pair{kInf, kInf}, std::pair{-kInf, -kInf}}) {
    SmallQp qp;
    qp.program.MutableRowLower()[0] = lower;
    qp.program.MutableRowUpper()[0] = upper;
    const optim::SolveResult result = optim::MakeSolver("active-set")->Solve(qp.program);
    CHECK(result.status == optim::SolveStatus::kInvalidInput);
  }
  {
    // 1e30 is "infinite" by the checked setter's convention (>= 1e20): the same impossible row.
    SmallQp qp;
    qp.program.SetConstraintBounds(qp.row, Eigen::VectorXd::Constant(1, 1e30), Eigen::VectorXd::Constant(1, 1e30));
    CHECK(optim::MakeSolver("active-set")->Solve(qp.program).status == optim::SolveStatus::kInvalidInput);
  }
  SmallQp qp;
  qp.program.MutableVariableLower()[1] = kInf;
  CHECK(optim::MakeSolver("active-set")->Solve(qp.program).status == optim::SolveStatus::kInvalidInput);
}

TEST_CASE("solver: badly scaled QPs return a status and, when solved, a finite feasible point", "[hardening][api][optim]") {
  // At the extreme scales (1e-150, 1e150) Ipopt runs to its iteration limit (3000 by default):
  // under the sanitizers, where its allocations per iteration made that most of a minute, a tenth
  // of it reaches the same status.
  optim::IpoptSettings ipopt;
  ipopt.max_iterations = stairplan::testing::FullOrSanitized(ipopt.max_iterations, 300);
  // A fresh solver for every problem: each solve is cold, as a user's first call would be.
  struct Named {
    const char* name;
    std::function<std::unique_ptr<optim::Solver>()> make;
  };
  const Named solvers[] = {{"active-set", [] { return optim::MakeSolver("active-set"); }},
                           {"ipopt", [&] { return std::make_unique<optim::IpoptSolver>(ipopt); }}};
  for (const double scale : {1e-150, 1e-12, 1.0, 1e12, 1e150}) {
    SmallQp qp;
    qp.program.MutableHessian() *= scale;
    for (const Named& solver : solvers) {
      INFO("Hessian scale " << scale << ", solver " << solver.name);
      const optim::SolveResult result = solver.make()->Solve(qp.program);
      if (result.status == optim::SolveStatus::kSolved) {
        REQUIRE(result.x.allFinite());
        const double sum = result.x.sum();
        CHECK(sum >= 1.0 - 1e-6);
        CHECK(sum <= 2.0 + 1e-6);
      }
    }
  }
}

TEST_CASE("body planner: a non-finite state or time throws naming it", "[hardening][api][body]") {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const RobotModel& robot = BuiltinRobot();
  const Plan footsteps = PlanCrawl(robot, stairs, map);
  REQUIRE(footsteps.status == PlanStatus::kOk);
  BodyPlanner planner(robot, stairs, map, footsteps);
  const BodyState start = planner.StartState();
  for (const double bad : {kNaN, kInf}) {
    BodyState state = start;
    state.z = bad;
    CHECK(ErrorOf([&] { planner.Update(state, BodyCommand{}, 0.0); }) != "accepted");
    state = start;
    state.pitch = bad;
    CHECK(ErrorOf([&] { planner.Update(state, BodyCommand{}, 0.0); }) != "accepted");
    CHECK(ErrorOf([&] { planner.Update(start, BodyCommand{}, bad); }) != "accepted");
    BodyCommand command;
    command.height_offset = bad;
    CHECK(ErrorOf([&] { planner.Update(start, command, 0.0); }) != "accepted");
  }
}
