// The clearance queries measure only the shape pairs their bounds cannot rule out, closest first.
// Over seeded random postures of Solo 12 (mesh hulls) and the built-in robot (primitives), near and
// into the stairs, their clearances equal those of measuring every pair, and the bounds they prune
// with never exceed a measured distance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <random>

#include "stairplan/collision/clearance.h"
#include "stairplan/collision/shape_support.h"
#include "stairplan/collision/signed_distance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "sanitized.h"
#include "shared_solo12.h"

using namespace stairplan;

namespace {

// Two pairs may be as close as each other to round-off (a foot in a tread block and in the nosing
// lip level with it), and another compiler may round the poses differently on the two paths (GJK
// stops within 1e-10): the distance kept may differ by this much, a nanometre [m].
constexpr double kSameDistance = 1e-9;

// Every shape pair of two legs measured (with the hints the queries give), in the base frame.
double EveryPairLegLeg(const RobotKinematics& kinematics, const RobotCollisionModel& robot, int a,
                       const Eigen::Vector3d& q_a, int b, const Eigen::Vector3d& q_b, RobotWorkspace& ws) {
  const std::vector<Eigen::Isometry3d> frames_a = kinematics.leg(a).LinkFrames(q_a, ws.leg(a));
  const std::vector<Eigen::Isometry3d> frames_b = kinematics.leg(b).LinkFrames(q_b, ws.leg(b));
  double best = std::numeric_limits<double>::infinity();
  for (const CollisionShape& sa : robot.leg_shapes(a)) {
    for (const CollisionShape& sb : robot.leg_shapes(b)) {
      const Eigen::Isometry3d pa = frames_a[static_cast<std::size_t>(sa.segment)] * sa.local;
      const Eigen::Isometry3d pb = frames_b[static_cast<std::size_t>(sb.segment)] * sb.local;
      SignedDistanceHints hints;
      hints.bounding_radius_a = sa.bounding_radius;
      hints.bounding_radius_b = sb.bounding_radius;
      const SignedDistanceResult r = SignedDistance(*sa.geometry, pa, *sb.geometry, pb, hints);
      const double d = r.distance;
      const double bound = SeparationLowerBound(*sa.geometry, pa, sa.bounding_radius, *sb.geometry, pb, sb.bounding_radius);
      if (d > 0.0) CHECK(bound <= d + 1e-9);
      best = std::min(best, d);
    }
  }
  return best;
}

// Every leg shape against every stair solid (no support plane skipped), in the world frame.
double EveryPairLegStairs(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                          const StairCollisionModel& stairs, int leg, const Eigen::Vector3d& q, const BodyPose& body,
                          RobotWorkspace& ws) {
  const std::vector<Eigen::Isometry3d> frames = kinematics.leg(leg).LinkFrames(q, ws.leg(leg));
  double best = std::numeric_limits<double>::infinity();
  for (const CollisionShape& shape : robot.leg_shapes(leg)) {
    const Eigen::Isometry3d pose = body.ToIsometry() * frames[static_cast<std::size_t>(shape.segment)] * shape.local;
    for (const StairSolid& solid : stairs.solids()) {
      SignedDistanceHints hints;
      hints.bounding_radius_a = shape.bounding_radius;
      hints.box_b = &solid.box;
      const double d = SignedDistance(*shape.geometry, pose, *solid.geometry, solid.pose, hints).distance;
      const double bound = BoxSeparationLowerBound(*shape.geometry, pose, shape.bounding_radius, solid.box);
      if (d > 0.0) CHECK(bound <= d + 1e-9);
      best = std::min(best, d);
    }
  }
  return best;
}

void CheckPrunedEqualsEveryPair(const RobotModel& model, int samples) {
  const RobotKinematics kinematics(model);
  const RobotCollisionModel robot(kinematics);
  const StairCollisionModel stairs{Staircase(StairSpec{})};
  RobotWorkspace ws(kinematics);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const NominalStance standing = NominalStanceAt(kinematics, ws, 0.0);
  ClearanceOptions every_solid;
  every_solid.skip_foot_support = false;
  int close_pairs = 0, close_stairs = 0;
  for (int sample = 0; sample < samples; ++sample) {
    std::array<Eigen::Vector3d, 4> q;
    for (int l = 0; l < 4; ++l) {
      const LegKinematics& leg = kinematics.leg(l);
      for (int j = 0; j < 3; ++j) q[l][j] = leg.lower()[j] + unit(rng) * (leg.upper()[j] - leg.lower()[j]);
    }
    BodyPose body = standing.body;
    body.position_W.x() = -0.3 + 1.2 * unit(rng);
    body.position_W.z() += 0.3 * (unit(rng) - 0.5) + 0.17 * (body.position_W.x() / 0.29);
    body.pitch = 0.4 * (unit(rng) - 0.5);
    for (const auto& [a, b] : {std::pair{0, 1}, std::pair{2, 3}, std::pair{0, 2}}) {
      const Clearance pruned = LegLegClearance(kinematics, robot, a, q[a], b, q[b], ws);
      const double every = EveryPairLegLeg(kinematics, robot, a, q[a], b, q[b], ws);
      CHECK(pruned.distance == Approx(every).margin(kSameDistance));
      close_pairs += every < 0.02;
    }
    for (int l = 0; l < 4; ++l) {
      const Clearance pruned = LegStairClearance(kinematics, robot, stairs, l, q[l], body, ws, every_solid);
      const double every = EveryPairLegStairs(kinematics, robot, stairs, l, q[l], body, ws);
      CHECK(pruned.distance == Approx(every).margin(kSameDistance));
      close_stairs += every < 0.02;
    }
  }
  // The postures do bring legs close to each other and to the stairs (the cases that matter).
  CHECK(close_pairs > 0);
  CHECK(close_stairs > 0);
}

}  // namespace

TEST_CASE("pruned clearances equal every pair's: the built-in robot's primitives", "[clearance][pruning]") {
  CheckPrunedEqualsEveryPair(BuiltinRobot(), testing::FullOrSanitized(300, 40));
}

TEST_CASE("pruned clearances equal every pair's: Solo 12's mesh hulls", "[clearance][pruning][solo12]") {
  const std::optional<RobotModel> solo = testing::SharedSolo12();
  if (!solo) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  CheckPrunedEqualsEveryPair(*solo, testing::FullOrSanitized(200, 25));
}
