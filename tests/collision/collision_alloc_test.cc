// Clearances and stance checks allocate nothing once the workspace exists (no penetration).
#include <catch2/catch.hpp>

#include "alloc_counter.h"
#include "collision/stance_check.h"
#include "kinematics/builtin_robot.h"

TEST_CASE("clearance and stance queries allocate nothing after warm-up", "[alloc][clearance]") {
  using namespace stairplan;
  StanceChecker checker(BuiltinRobot(), Staircase(StairSpec{}));
  BodyPose body;
  body.position_W = {-0.8, 0.0, 0.47};
  std::array<Eigen::Vector3d, 4> contacts;
  for (int l = 0; l < 4; ++l) {
    const auto& leg = checker.kinematics().leg(l);
    const Eigen::Vector3d foot = body.ToIsometry() * leg.FootPosition(leg.nominal(), checker.workspace().leg(l));
    contacts[static_cast<std::size_t>(l)] = {foot.x(), foot.y(), 0.0};
  }
  const StanceResult warm = checker.Check(body, contacts);
  REQUIRE(warm.ok());
  testing::AllocationScope scope;
  const StanceResult r = checker.Check(body, contacts);
  const Clearance c = LegStairClearance(checker.kinematics(), checker.collision_model(), checker.stairs(), 0,
                                        r.legs[0].ik.q, body, checker.workspace());
  CHECK(scope.count() == 0);
  CHECK(c.distance > 0.0);
}
