// Leg-versus-stairs and leg-versus-leg clearances on stairbot, against hand computations.
#include <catch2/catch.hpp>

#include <random>

#include "collision/clearance.h"
#include "kinematics/builtin_robot.h"

using namespace stairplan;

namespace {

struct Fixture {
  RobotKinematics kinematics{BuiltinRobot()};
  RobotCollisionModel robot{kinematics};
  Staircase staircase{StairSpec{}};  // 7 x 0.17 rise, 0.27 run, 0.02 nosing, ascending
  StairCollisionModel stairs{staircase};
  RobotWorkspace ws{kinematics};
  int lf = kinematics.LegIndex("LF");

  // The level body placed so that LF's foot centre is at foot_W with joint angles q.
  BodyPose BodyFor(const Eigen::Vector3d& q, const Eigen::Vector3d& foot_W) {
    BodyPose body;
    body.position_W = foot_W - kinematics.leg(lf).FootPosition(q, ws.leg(lf));
    return body;
  }
};

}  // namespace

TEST_CASE("a foot hovering 3 cm over a tread is 3 cm clear", "[clearance]") {
  Fixture f;
  // Tread 1 spans x [-0.02, 0.25] at z = 0.17.
  REQUIRE(f.staircase.surface(1).z == Approx(0.17));
  const Eigen::Vector3d q(0.0, 0.5, -0.5);  // shank vertical
  const BodyPose body = f.BodyFor(q, {0.10, 0.18, 0.17 + 0.025 + 0.03});
  ClearanceOptions options;
  options.skip_foot_support = false;
  const Clearance c = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, body, f.ws, options);
  CHECK(c.distance == Approx(0.03).margin(1e-6));
  CHECK(c.part == StairPart::kTread);
  CHECK(c.point_other_W.z() == Approx(0.17).margin(1e-6));
  CHECK(f.robot.leg_shapes(f.lf)[static_cast<std::size_t>(c.shape)].foot_contact);
}

TEST_CASE("standing on a tread, the shank's end is the closest part", "[clearance]") {
  Fixture f;
  const Eigen::Vector3d q(0.0, 0.5, -0.5);
  const BodyPose body = f.BodyFor(q, {0.10, 0.18, 0.17 + 0.025});
  const Clearance c = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, body, f.ws);
  // Shank cylinder: 0.02 to 0.24 below the knee, the foot 0.30 below: its end is 6 cm above the
  // foot centre, i.e. 0.025 + 0.06 above the tread.
  CHECK(c.distance == Approx(0.085).margin(1e-6));
  CHECK(c.part == StairPart::kTread);
  CHECK(f.robot.leg_shapes(f.lf)[static_cast<std::size_t>(c.shape)].link == "LF_shank");
}

TEST_CASE("a foot near the riser: the shank meets the nosing above first", "[clearance]") {
  Fixture f;
  const Eigen::Vector3d q(0.0, 0.5, -0.5);
  // Riser 2 at x = 0.27, the nosing lip in front of it at x [0.25, 0.27], z [0.31, 0.34].
  const BodyPose body = f.BodyFor(q, {0.20, 0.18, 0.17 + 0.025});
  const Clearance c = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, body, f.ws);
  CHECK(c.distance == Approx(0.25 - (0.20 + 0.018)).margin(1e-6));
  CHECK(c.part == StairPart::kNosing);
  CHECK(c.point_other_W.x() == Approx(0.25).margin(1e-6));
  // 1 cm further the shank is inside the lip by the same amount it is now clear of it.
  const BodyPose deeper = f.BodyFor(q, {0.20 + 0.032 + 0.010, 0.18, 0.17 + 0.025});
  const Clearance inside = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, deeper, f.ws);
  CHECK(inside.distance == Approx(-0.010).margin(1e-6));
}

TEST_CASE("contralateral front legs: hip cylinders 0.2 m apart", "[clearance]") {
  Fixture f;
  const Eigen::Vector3d q(0.0, 0.73, -1.46);
  const Clearance c = LegLegClearance(f.kinematics, f.robot, 0, q, 1, q, f.ws);
  CHECK(c.distance == Approx(0.20).margin(1e-6));
  CHECK(f.robot.leg_shapes(0)[static_cast<std::size_t>(c.shape)].link == "LF_hip");
  // Abducting both legs inwards by 0.3 rad brings the feet together: much closer.
  const Clearance inward = LegLegClearance(f.kinematics, f.robot, 0, Eigen::Vector3d(-0.45, 0.73, -1.46), 1,
                                           Eigen::Vector3d(0.45, 0.73, -1.46), f.ws);
  CHECK(inward.distance < 0.1);
}

TEST_CASE("the body is clear of the stairs when standing on the landing", "[clearance]") {
  Fixture f;
  BodyPose body;
  body.position_W = {-1.0, 0.0, 0.45};
  const Clearance c = BodyStairClearance(f.robot, f.stairs, body);
  CHECK(c.distance == Approx(0.45 - 0.06).margin(1e-6));  // box 0.12 high, landing at z = 0
  CHECK(c.leg == -1);
}

TEST_CASE("a pruned clearance agrees with the exact one about the margin, and is exact below it", "[clearance]") {
  Fixture f;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> x(-0.1, 0.6), z(0.15, 0.45);
  const LegKinematics& leg = f.kinematics.leg(f.lf);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr double kMargin = 0.01;
  ClearanceOptions pruned;
  pruned.prune_above = kMargin;
  int below = 0, above = 0;
  for (int i = 0; i < 400; ++i) {
    Eigen::Vector3d q;
    for (int j = 0; j < 3; ++j) q(j) = leg.lower()(j) + u(rng) * (leg.upper()(j) - leg.lower()(j));
    const BodyPose body = f.BodyFor(q, {x(rng), 0.18, z(rng)});
    const Clearance exact = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, body, f.ws);
    const Clearance cheap = LegStairClearance(f.kinematics, f.robot, f.stairs, f.lf, q, body, f.ws, pruned);
    INFO("sample " << i << ": exact " << exact.distance << ", pruned " << cheap.distance);
    REQUIRE((exact.distance > kMargin) == (cheap.distance > kMargin));
    if (exact.distance < kMargin) {
      CHECK(cheap.distance == exact.distance);
      ++below;
    } else {
      CHECK(cheap.distance >= kMargin);
      ++above;
    }
    const Clearance pair = LegLegClearance(f.kinematics, f.robot, 0, q, 1, q, f.ws, kMargin);
    const Clearance pair_exact = LegLegClearance(f.kinematics, f.robot, 0, q, 1, q, f.ws);
    REQUIRE((pair.distance > kMargin) == (pair_exact.distance > kMargin));
  }
  // Both sides of the margin were sampled, so the agreement means something.
  CHECK(below > 20);
  CHECK(above > 20);
}
