// Clearances and stance checks allocate nothing once the workspace exists, whether legs are clear
// of the stairs or penetrate them.
#include <catch2/catch.hpp>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include "alloc_counter.h"
#include "stairplan/collision/signed_distance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/builtin_robot.h"

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

TEST_CASE("penetrating boxes, cylinders and spheres allocate nothing either", "[alloc][clearance]") {
  using namespace stairplan;
  const Staircase stairs{StairSpec{}};
  const Box3 step = stairs.Solids().front();
  const fcl::Boxd step_geometry(step.Size()), thigh(0.05, 0.04, 0.26);
  const fcl::Cylinderd shank(0.02, 0.2);
  const fcl::Sphered foot(0.03);
  SignedDistanceHints hints;
  hints.box_b = &step;
  Eigen::Isometry3d step_pose = Eigen::Isometry3d::Identity();
  step_pose.translation() = step.Center();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = step.Center() + Eigen::Vector3d(0.0, 0.0, 0.5 * step.Size().z());  // half in, half out
  double depth = 0.0;
  const auto query = [&] {
    depth = std::min(depth, SignedDistance(thigh, pose, step_geometry, step_pose, hints).distance);
    depth = std::min(depth, SignedDistance(shank, pose, step_geometry, step_pose, hints).distance);
    depth = std::min(depth, SignedDistance(foot, pose, step_geometry, step_pose, hints).distance);
  };
  query();  // FCL's solvers set themselves up on first use
  testing::AllocationScope scope;
  query();
  CHECK(scope.count() == 0);
  CHECK(depth < -0.01);
}
