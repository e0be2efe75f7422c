// Leg-versus-stairs and leg-versus-leg clearances on stairbot, against hand computations; the
// foot-support rule for the foot's parts on a collared stairbot and on ANYmal B.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "../kinematics/robot_files.h"
#include "stairplan/collision/clearance.h"
#include "stairplan/kinematics/builtin_robot.h"

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
  // foot centre, i.e. 0.025 + 0.06 above the tread. The shank is the knee's link, not a part of
  // the foot: it keeps seeing the tread it stands on.
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

namespace {

// stairbot with a collar on LF's foot link: a disk of radius 0.04 (wider than the 0.025 sphere)
// and 1 cm thick whose bottom is 5 mm above the sphere's lowest point while the shank is upright.
// Tilting the leg by p lowers the collar's rim to 0.025 - 0.020 cos p - 0.04 sin p above the
// sphere's contact, below it beyond 7.6 degrees.
struct CollarFixture {
  static RobotModel Robot() {
    std::string xml = BuiltinRobotUrdf();
    const std::string foot = "<link name=\"LF_foot\">";
    const std::size_t at = xml.find(foot);
    REQUIRE(at != std::string::npos);
    xml.insert(at + foot.size(),
               "<collision><origin xyz=\"0 0 -0.015\" rpy=\"0 0 0\"/>"
               "<geometry><cylinder radius=\"0.04\" length=\"0.01\"/></geometry></collision>");
    return RobotModel::FromUrdfString(xml, "collared stairbot");
  }
  RobotKinematics kinematics{Robot()};
  RobotCollisionModel robot{kinematics};
  StairCollisionModel stairs{Staircase{StairSpec{}}};  // tread 1 at z = 0.17, riser 2 at x = 0.27
  RobotWorkspace ws{kinematics};
  int lf = kinematics.LegIndex("LF");
  Eigen::Vector3d upright{0.0, 0.5, -0.5};  // the shank vertical in the body frame

  // The body pitched by `pitch` with LF's sphere resting on tread 1 at x (the leg tilts with it).
  BodyPose StandingAt(double x, double pitch) {
    BodyPose body;
    body.pitch = pitch;
    const Eigen::Vector3d centre_W(x, 0.18, 0.17 + 0.025);
    body.position_W = centre_W - body.ToIsometry().linear() * kinematics.leg(lf).FootPosition(upright, ws.leg(lf));
    return body;
  }
  Clearance At(double x, double pitch) {
    return LegStairClearance(kinematics, robot, stairs, lf, upright, StandingAt(x, pitch), ws);
  }
  bool IsCollar(const Clearance& c) const {
    return robot.leg_shapes(lf).at(static_cast<std::size_t>(c.shape)).type == ShapeType::kCylinder &&
           robot.leg_shapes(lf).at(static_cast<std::size_t>(c.shape)).link == "LF_foot";
  }
  // The tilt that puts the collar's lowest point `below` under the sphere's contact: solves
  // 0.020 cos p + 0.04 sin p = 0.025 + below.
  static double TiltFor(double below) {
    return std::atan2(0.04, 0.02) - std::acos((0.025 + below) / std::hypot(0.02, 0.04));
  }
};

}  // namespace

TEST_CASE("a collar on the foot, above the tread the foot stands on, ignores that tread", "[clearance]") {
  CollarFixture f;
  // Upright, 5 mm above tread 1: the nearest obstacle is the shank's end, 0.085 above the same
  // tread (the knee's link, not a foot part); the collar's own nearest is riser 2, 0.13 away.
  const Clearance upright = f.At(0.10, 0.0);
  CHECK(upright.distance == Approx(0.085).margin(1e-6));
  CHECK(upright.part == StairPart::kTread);
  CHECK_FALSE(f.IsCollar(upright));
  // Tilted until its rim is 1 mm above the contact: still no obstacle there, at any margin (the
  // shank's end, tilted too, comes no nearer than 7 cm).
  const Clearance tilted = f.At(0.10, CollarFixture::TiltFor(-0.001));
  CHECK(tilted.distance > 0.07);
  CHECK_FALSE(f.IsCollar(tilted));
}

TEST_CASE("the same collar tilted 1 mm into the tread the foot stands on collides with it", "[clearance]") {
  CollarFixture f;
  const double tilt = CollarFixture::TiltFor(0.001);
  REQUIRE(tilt * 180.0 / M_PI == Approx(8.98).margin(0.01));  // by hand: 63.43 - 54.45 degrees
  const Clearance c = f.At(0.10, tilt);
  CHECK(c.distance == Approx(-0.001).margin(1e-6));
  CHECK(c.part == StairPart::kTread);
  CHECK(c.point_other_W.z() == Approx(0.17).margin(1e-6));
  CHECK(f.IsCollar(c));
  // Tilted the other way, the opposite rim dips as deep.
  const Clearance mirrored = f.At(0.10, -tilt);
  CHECK(mirrored.distance == Approx(-0.001).margin(1e-6));
}

TEST_CASE("a collar on the foot still meets the riser ahead of its tread", "[clearance]") {
  CollarFixture f;
  // Foot 0.22 along tread 1: the collar's edge is 1 cm from riser 2 (x = 0.27), the sphere's 2.5
  // cm, the shank's 1.2 cm from the nosing lip's front (x = 0.25).
  const Clearance near = f.At(0.22, 0.0);
  CHECK(near.distance == Approx(0.01).margin(1e-6));
  CHECK(near.part == StairPart::kRiser);
  CHECK(f.IsCollar(near));
  // 2 cm further the collar is 1 cm inside the riser.
  const Clearance inside = f.At(0.24, 0.0);
  CHECK(inside.distance == Approx(-0.01).margin(1e-6));
  CHECK(f.IsCollar(inside));
}

TEST_CASE("ANYmal B's adapter tube never dips below its foot's contact, so standing it is clear of the ground",
          "[clearance]") {
  const auto robots = testing::TestRobots(false);
  const auto b = std::find_if(robots.begin(), robots.end(), [](const testing::RobotFile& r) { return r.label == "anymal_b"; });
  if (b == robots.end()) {
    WARN("ANYmal B skipped: ../shared not found");
    return;
  }
  const RobotKinematics kinematics(RobotModel::FromUrdfFile(b->path));
  const RobotCollisionModel robot(kinematics);
  const StairCollisionModel stairs{Staircase{StairSpec{}}};  // the landing at z = 0 ends at x = 0
  RobotWorkspace ws(kinematics);
  const int lf = kinematics.LegIndex("LF");
  const LegKinematics& leg = kinematics.leg(lf);
  const auto& shapes = robot.leg_shapes(lf);
  const auto adapter = std::find_if(shapes.begin(), shapes.end(), [](const CollisionShape& s) { return s.link == "LF_ADAPTER"; });
  REQUIRE(adapter != shapes.end());
  REQUIRE(adapter->foot_part);
  const Eigen::Vector3d q = leg.nominal();
  const Eigen::Isometry3d foot_B = leg.FootPose(q, ws.leg(lf));
  const Eigen::Vector3d axis_B = foot_B.linear().col(2);  // the tube's axis
  for (int degrees = 0; degrees <= 45; degrees += 5) {  // the tube comes closest at 32.8
    const double tilt = degrees * M_PI / 180.0;
    // Pitch the body so that the tube leans `tilt` from vertical; the sphere rests on the landing
    // half a metre before the first riser (nothing else near).
    BodyPose body;
    body.pitch = tilt - std::atan2(axis_B.x(), axis_B.z());
    const Eigen::Isometry3d base = body.ToIsometry();
    const Eigen::Vector3d centre_W(-0.5, 0.0, leg.model().foot_radius);
    body.position_W = centre_W - base.linear() * (foot_B * leg.model().foot_sphere_center);
    const std::vector<Eigen::Isometry3d>& frames = leg.LinkFrames(q, ws.leg(lf));
    const Eigen::Isometry3d tube_W = body.ToIsometry() * frames[static_cast<std::size_t>(adapter->segment)] * adapter->local;
    // By hand: sphere centre 0.031 above the tread, the tube's end 0.02325 below it along the axis,
    // its rim 0.015 from the axis.
    const double above = 0.031 - 0.02325 * std::cos(tilt) - 0.015 * std::sin(tilt);
    INFO(degrees << " degrees");
    CHECK(LowestZ(*adapter, tube_W) == Approx(above).margin(1e-9));
    CHECK(above > 0.0033);
    // At the planners' 5 mm margin the leg is no collision at any of these tilts (the tube was
    // one from 13 degrees on while it did not ignore the landing).
    const Clearance c = LegStairClearance(kinematics, robot, stairs, lf, q, body, ws);
    CHECK(c.distance > 0.005);
  }
}
