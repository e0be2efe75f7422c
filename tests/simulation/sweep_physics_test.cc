#include <catch2/catch.hpp>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/simulation/sweep_physics.h"

using namespace stairplan;

TEST_CASE("sweep physics skips points without a plan and keeps rows in point order", "[simulation]") {
  SweepPhysics physics;
  const RobotModel& robot = BuiltinRobot();
  const Staircase stairs(StairSpec{});
  PipelineResult infeasible;
  infeasible.plan.status = PlanStatus::kInfeasible;
  SweepPoint point;
  point.index = 4;
  physics.Record(point, robot, stairs, infeasible);
  CHECK(physics.Rows().empty());
  // A plan that cannot be executed (no body samples) is a row with status "error", not a throw.
  PipelineResult broken;
  broken.validation.ok = true;
  physics.Record(point, robot, stairs, broken);
  point.index = 2;
  physics.Record(point, robot, stairs, broken);
  const std::vector<PhysicsRow> rows = physics.Rows();
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].index == 2);
  CHECK(rows[1].status == "error");
  CHECK(rows[1].cause.find("plan.body") != std::string::npos);
  CHECK(physics.Csv().rfind("index,point,validator,", 0) == 0);
  const AgreementReport agreement = physics.Agreement();
  CHECK(agreement.compared == 2);
  CHECK(agreement.valid_but_failed.size() == 2);
}
