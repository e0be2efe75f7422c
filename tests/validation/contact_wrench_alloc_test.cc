// The dynamic check per instant allocates nothing after its first solve: the validator runs it at
// every replayed instant (about 2,000 for the default flight).
#include <catch2/catch.hpp>

#include <cmath>

#include "alloc_counter.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "nominal_stance.h"
#include "stairplan/planning/validation/contact_wrench_check.h"

using namespace stairplan;

TEST_CASE("the dynamic check allocates nothing per instant after warm-up", "[dynamics][alloc]") {
  const RobotKinematics kinematics(BuiltinRobot());
  RobotWorkspace ws(kinematics);
  ContactWrenchCheck check(kinematics, BuiltinRobot().total_mass());
  WrenchInstant instant = testing::NominalStance(kinematics, ws);
  const auto step = [&](int k) {
    instant.stance[static_cast<std::size_t>(k % 4)] = k % 3 != 0;  // a foot lifts and lands
    instant.com_W = {0.02 * std::sin(0.3 * k), 0.02 * std::cos(0.2 * k), 0.4};
    instant.rates.linear_W = {3.0 * std::sin(0.1 * k), 0.0, 0.5 * std::cos(0.1 * k)};
    instant.rates.angular_W = {0.0, std::sin(0.05 * k), 0.0};
    return check.Check(instant, ws).residual;
  };
  for (int k = 0; k < 20; ++k) step(k);  // warm-up: the solver sizes its workspace
  double residual = 0.0;
  testing::AllocationScope scope;
  for (int k = 20; k < 220; ++k) residual += step(k);
  CHECK(scope.count() == 0);
  CHECK(std::isfinite(residual));
}
