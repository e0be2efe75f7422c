// The exact re-check of a body trajectory (body_check.h): every leg, stance or swing, the body
// and the pairs of neighbouring legs.
#include <catch2/catch.hpp>

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/shapes.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_check.h"

using namespace stairplan;

namespace {

// The built-in robot standing in its nominal stance on the landing before the default stairs,
// as a plan with no footsteps, and the body there.
struct Standing {
  Plan plan;
  BodyState body;
};

Standing StandingAt(const RobotKinematics& kinematics, double x) {
  RobotWorkspace ws(kinematics);
  const NominalStance nominal = NominalStanceAt(kinematics, ws, x);
  Standing s;
  for (int l = 0; l < 4; ++l) {
    s.plan.legs.push_back(kinematics.leg(l).name());
    s.plan.initial_feet_W.push_back(nominal.contacts_W[static_cast<std::size_t>(l)]);
  }
  s.body.x = nominal.body.position_W.x();
  s.body.y = nominal.body.position_W.y();
  s.body.z = nominal.body.position_W.z();
  return s;
}

BodyPlanCheck Check(const Standing& s, const Staircase& stairs) {
  KinematicBodyBounds bounds(BuiltinRobot(), stairs, Facing::kForward);
  return CheckBodyTrajectory(bounds, FootSchedule(BuiltinRobot(), s.plan), {s.body}, BodyCheckMargins{0.005});
}

}  // namespace

TEST_CASE("the body re-check passes the nominal stance and names the legs of a crossed pair", "[body][check]") {
  const Staircase stairs{StairSpec{}};
  const RobotKinematics kinematics(BuiltinRobot());
  Standing s = StandingAt(kinematics, -1.0);
  const BodyPlanCheck nominal = Check(s, stairs);
  INFO(nominal.first_violation);
  CHECK(nominal.ok());
  CHECK(nominal.samples == 1);
  CHECK(nominal.min_clearance > 0.005);

  // The right hind foot moved up to 3 cm behind the right front one, under the body's middle:
  // both legs reach, and their shanks stand side by side.
  const int rf = kinematics.LegIndex("RF"), rh = kinematics.LegIndex("RH");
  Eigen::Vector3d& hind = s.plan.initial_feet_W[static_cast<std::size_t>(rh)];
  const Eigen::Vector3d& front = s.plan.initial_feet_W[static_cast<std::size_t>(rf)];
  hind.x() = s.body.x - 0.015;
  s.plan.initial_feet_W[static_cast<std::size_t>(rf)].x() = s.body.x + 0.015;
  REQUIRE(hind.x() < front.x());
  const BodyPlanCheck crossed = Check(s, stairs);
  INFO(crossed.first_violation);
  CHECK_FALSE(crossed.ok());
  CHECK(crossed.first_violation == "t=0.000 s, RF/RH: legs closer than the margin");
}

TEST_CASE("the body re-check looks between the body's samples: two instants in each interval", "[body][check]") {
  // Three samples 50 ms apart, the middle one raised 4 cm: each interval is checked at its thirds
  // too, and the body there is between its samples (a leg that reaches both ends reaches them).
  const Staircase stairs{StairSpec{}};
  const RobotKinematics kinematics(BuiltinRobot());
  const Standing s = StandingAt(kinematics, -1.0);
  std::vector<BodyState> body(3, s.body);
  for (std::size_t i = 0; i < body.size(); ++i) body[i].t = 0.05 * static_cast<double>(i);
  body[1].z += 0.04;
  KinematicBodyBounds bounds(BuiltinRobot(), stairs, Facing::kForward);
  const BodyPlanCheck check = CheckBodyTrajectory(bounds, FootSchedule(BuiltinRobot(), s.plan), body, BodyCheckMargins{0.005});
  INFO(check.first_violation);
  CHECK(check.ok());
  CHECK(check.samples == 3);
  CHECK(check.instants == 1 + 2 * 3);
}

TEST_CASE("the body re-check keeps the body itself off the stairs", "[body][check]") {
  // Standing with its body centre over the first nosing, 2 cm above the first tread: the legs
  // stand on the landing, the body is in the first step.
  const Staircase stairs{StairSpec{}};
  const RobotKinematics kinematics(BuiltinRobot());
  Standing s = StandingAt(kinematics, -1.0);
  const BodyPlanCheck far = Check(s, stairs);
  REQUIRE(far.ok());
  s.body.x = 0.0;
  s.body.z = stairs.spec().rise + 0.02;
  const BodyPlanCheck into = Check(s, stairs);
  CHECK_FALSE(into.ok());
  CHECK_THAT(into.first_violation, Catch::StartsWith("t=0.000 s, body: clearance below the margin"));
}

TEST_CASE("the body re-check measures the centre of mass inside the standing feet", "[body][check]") {
  // Standing in its nominal stance the centre of mass is near the middle of the four feet: its
  // margin is about the body's distance from the nearest side of their rectangle (the legs' links
  // move it by millimetres). A margin wider than that is refused, naming the body.
  const Staircase stairs{StairSpec{}};
  const RobotKinematics kinematics(BuiltinRobot());
  const Standing s = StandingAt(kinematics, -1.0);
  std::vector<Eigen::Vector2d> feet;
  for (const Eigen::Vector3d& f : s.plan.initial_feet_W) feet.push_back(f.head<2>());
  const double inside = -ConvexHull(feet).SignedDistance({s.body.x, s.body.y});
  REQUIRE(inside > 0.05);
  KinematicBodyBounds bounds(BuiltinRobot(), stairs, Facing::kForward);
  const FootSchedule schedule(BuiltinRobot(), s.plan);
  const BodyPlanCheck kept = CheckBodyTrajectory(bounds, schedule, {s.body}, BodyCheckMargins{0.005, inside - 0.02});
  INFO(kept.Summary());
  CHECK(kept.ok());
  CHECK(kept.min_stability_margin == Approx(inside).margin(0.01));
  const BodyPlanCheck refused = CheckBodyTrajectory(bounds, schedule, {s.body}, BodyCheckMargins{0.005, inside + 0.02});
  CHECK(refused.violations == 1);
  CHECK(refused.first_violation == "t=0.000 s, body: centre of mass closer than the stability margin to the support's edge");
  // Not asked for (a dynamic gait's plan): not measured.
  CHECK(CheckBodyTrajectory(bounds, schedule, {s.body}, BodyCheckMargins{0.005}).min_stability_margin ==
        std::numeric_limits<double>::infinity());
}

TEST_CASE("the body re-check refuses a body that moves back along the travel beyond the bound", "[body][check]") {
  // Standing, the body sways 2 cm forward and back, then 1.5 cm behind its farthest: measured
  // from the farthest sample, not the last one.
  const Staircase stairs{StairSpec{}};
  const RobotKinematics kinematics(BuiltinRobot());
  const Standing s = StandingAt(kinematics, -1.0);
  std::vector<BodyState> body(4, s.body);
  const std::array<double, 4> x = {0.0, 0.02, 0.012, 0.005};
  for (std::size_t i = 0; i < body.size(); ++i) {
    body[i].t = 0.05 * static_cast<double>(i);
    body[i].x += x[i];
  }
  KinematicBodyBounds bounds(BuiltinRobot(), stairs, Facing::kForward);
  const FootSchedule schedule(BuiltinRobot(), s.plan);
  BodyCheckMargins margins{0.005};
  margins.retreat = 0.02;
  const BodyPlanCheck within = CheckBodyTrajectory(bounds, schedule, body, margins);
  INFO(within.Summary());
  CHECK(within.ok());
  CHECK(within.max_retreat == Approx(0.015));
  margins.retreat = 0.01;
  const BodyPlanCheck beyond = CheckBodyTrajectory(bounds, schedule, body, margins);
  CHECK(beyond.violations == 1);
  CHECK(beyond.first_violation == "t=0.150 s, body: moved back along the travel by more than the bound");
}
