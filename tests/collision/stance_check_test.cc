// StanceCheck: IK of all four feet for a body pose, limits and clearances.
#include <catch2/catch.hpp>

#include <random>

#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/builtin_robot.h"

using namespace stairplan;

namespace {

// Contacts under stairbot's nominal feet for a level body at `body`.
std::array<Eigen::Vector3d, 4> NominalContacts(StanceChecker& checker, const BodyPose& body, double ground_z) {
  std::array<Eigen::Vector3d, 4> contacts;
  for (int l = 0; l < 4; ++l) {
    const auto& leg = checker.kinematics().leg(l);
    Eigen::Vector3d foot_W = body.ToIsometry() * leg.FootPosition(leg.nominal(), checker.workspace().leg(l));
    contacts[static_cast<std::size_t>(l)] = {foot_W.x(), foot_W.y(), ground_z};
  }
  return contacts;
}

}  // namespace

TEST_CASE("standing on the landing in the nominal pose is ok", "[stance_check]") {
  StanceChecker checker(BuiltinRobot(), Staircase(StairSpec{}));
  BodyPose body;
  const double foot_drop = -checker.kinematics().leg(0).FootPosition(checker.kinematics().leg(0).nominal(),
                                                                    checker.workspace().leg(0)).z();
  body.position_W = {-0.8, 0.0, foot_drop + 0.025};
  const StanceResult r = checker.Check(body, NominalContacts(checker, body, 0.0));
  CHECK(r.ok());
  CHECK(std::string(ToString(r.status)) == "ok");
  for (int l = 0; l < 4; ++l) {
    CHECK(r.legs[static_cast<std::size_t>(l)].ik.ok());
    CHECK((r.legs[static_cast<std::size_t>(l)].ik.q - checker.kinematics().leg(l).nominal()).norm() < 1e-6);
  }
  CHECK(r.min_clearance > 0.05);
  CHECK(r.front_pair.distance > 0.1);
}

TEST_CASE("a body too high is out of reach, a foot against the riser collides", "[stance_check]") {
  StanceChecker checker(BuiltinRobot(), Staircase(StairSpec{}));
  BodyPose body;
  body.position_W = {-0.8, 0.0, 0.7};
  auto contacts = NominalContacts(checker, body, 0.0);
  CHECK(checker.Check(body, contacts).status == StanceStatus::kOutOfReach);
  // LF's foot pushed against the first riser (x = 0 at z 0..0.17), the body level above.
  body.position_W = {-0.40, 0.0, 0.48};  // RF's foot 10 cm before the riser
  contacts = NominalContacts(checker, body, 0.0);
  contacts[0].x() = -0.01;
  const StanceResult r = checker.Check(body, contacts);
  REQUIRE(r.legs[0].ik.ok());
  CHECK(r.status == StanceStatus::kCollision);
  CHECK(r.worst_leg == 0);
  CHECK(r.min_clearance < 0.0);
  CHECK(r.legs[0].stairs.part == StairPart::kRiser);
}

TEST_CASE("CheckStance refuses NaN contacts", "[stance_check]") {
  StanceChecker checker(BuiltinRobot(), Staircase(StairSpec{}));
  std::array<Eigen::Vector3d, 4> contacts;
  contacts.fill(Eigen::Vector3d::Zero());
  contacts[2].x() = NAN;
  CHECK_THROWS_WITH(checker.Check(BodyPose{}, contacts), Catch::Contains("contacts_W[2]"));
}

TEST_CASE("feasible body heights bracket the nominal standing height on flat ground", "[stance_check]") {
  StanceChecker checker(BuiltinRobot(), Staircase(StairSpec{}));
  BodyPose body;
  body.position_W = {-0.8, 0.0, 0.47};
  const auto contacts = NominalContacts(checker, body, 0.0);
  const Interval1 heights = checker.FeasibleBodyHeights(body, contacts, 0.0, 0.8);
  REQUIRE_FALSE(heights.empty());
  CHECK(heights.lo < 0.47);
  CHECK(heights.hi > 0.47);
  // stairbot's leg is at most 0.596 m long (knee limit): the body cannot be higher than that
  // above the foot centres, which sit 0.025 above the ground.
  CHECK(heights.hi < 0.025 + 0.596 + 1e-3);
  body.position_W.z() = heights.hi + 0.01;
  CHECK_FALSE(checker.Check(body, contacts).ok());
  body.position_W.z() = heights.lo - 0.01;
  CHECK_FALSE(checker.Check(body, contacts).ok());
}

TEST_CASE("a pruned check measures every clearance below its bound as the full check does, and reads the rest as beyond it",
          "[stance_check]") {
  // Seeded random bodies over the first steps, the feet under their nominal places on the stairs
  // (some out of reach, some legs in the risers), pruned at bounds from the check's margin to a
  // decimetre: what the validator keeps (clearances below its margin and the smallest so far) is
  // the same either way, and so is the verdict.
  const Staircase stairs{StairSpec{}};
  StanceChecker checker(BuiltinRobot(), stairs);
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> x(-0.5, 0.6), dz(-0.08, 0.05), pitch(-0.5, 0.2), bound(1e-6, 0.1);
  const auto same_or_beyond = [](const Clearance& full, const Clearance& pruned, double prune) {
    if (full.distance < prune) {
      CHECK(pruned.distance == full.distance);
    } else {
      CHECK(pruned.distance >= prune);
    }
  };
  int measured_below = 0;
  for (int trial = 0; trial < 300; ++trial) {
    BodyPose body;
    body.position_W = {x(rng), 0.0, 0.0};
    body.pitch = pitch(rng);
    std::array<Eigen::Vector3d, 4> contacts;
    for (int l = 0; l < 4; ++l) {
      const auto& leg = checker.kinematics().leg(l);
      const Eigen::Vector3d foot = body.ToIsometry() * leg.FootPosition(leg.nominal(), checker.workspace().leg(l));
      contacts[static_cast<std::size_t>(l)] = {foot.x(), foot.y(), stairs.HeightAt(foot.x(), foot.y())};
    }
    body.position_W.z() = stairs.HeightAt(body.position_W.x(), 0.0) + 0.3 + dz(rng);
    const double prune = bound(rng);
    INFO("trial " << trial << ", pruned above " << prune);
    const StanceResult full = checker.Check(body, contacts);
    const StanceResult pruned = checker.Check(body, contacts, prune);
    CHECK(pruned.status == full.status);
    for (std::size_t l = 0; l < 4; ++l) same_or_beyond(full.legs[l].stairs, pruned.legs[l].stairs, prune);
    same_or_beyond(full.body, pruned.body, prune);
    for (const auto& [f, p] : {std::pair{&full.front_pair, &pruned.front_pair}, {&full.hind_pair, &pruned.hind_pair},
                               {&full.left_pair, &pruned.left_pair}, {&full.right_pair, &pruned.right_pair}}) {
      same_or_beyond(*f, *p, prune);
      measured_below += f->distance < prune ? 1 : 0;
    }
    measured_below += full.min_clearance < prune ? 1 : 0;
  }
  CHECK(measured_below > 50);  // the bounds cut through the clearances the trials met
  // A judge's bound sits just above both what it keeps: the margin and the smallest so far.
  CHECK(JudgePruneBound(0.02, 0.005) > 0.02);
  CHECK(JudgePruneBound(0.02, 0.005) < 0.02 + 1e-5);
  CHECK(JudgePruneBound(0.001, 0.005) > 0.005);
}
