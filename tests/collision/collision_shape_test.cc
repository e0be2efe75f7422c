// Collision primitives: the lowest point of a posed box, cylinder and sphere, against hand values.
#include <catch2/catch.hpp>

#include <cmath>

#include "stairplan/collision/collision_shape.h"

using namespace stairplan;

namespace {

CollisionShape BareShape(ShapeType type, const Eigen::Vector3d& size) {
  CollisionShape s;
  s.type = type;
  s.size = size;
  return s;
}

Eigen::Isometry3d PitchedAt(const Eigen::Vector3d& centre, double pitch) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = centre;
  return pose;
}

}  // namespace

TEST_CASE("LowestZ: a box's lowest corner, upright and turned", "[collision_shape]") {
  const CollisionShape box = BareShape(ShapeType::kBox, {0.2, 0.1, 0.06});
  CHECK(LowestZ(box, PitchedAt({0.0, 0.0, 1.0}, 0.0)) == Approx(1.0 - 0.03).margin(1e-12));
  // Turned 45 degrees about y: the corner is (0.1 + 0.03) / sqrt(2) below the centre.
  CHECK(LowestZ(box, PitchedAt({0.0, 0.0, 1.0}, M_PI / 4)) == Approx(1.0 - 0.13 / std::sqrt(2.0)).margin(1e-12));
  // On its end: half the length below.
  CHECK(LowestZ(box, PitchedAt({0.0, 0.0, 1.0}, -M_PI / 2)) == Approx(1.0 - 0.1).margin(1e-12));
}

TEST_CASE("LowestZ: a cylinder's lower rim, upright, tilted and lying", "[collision_shape]") {
  const CollisionShape tube = BareShape(ShapeType::kCylinder, {0.015, 0.015, 0.32});  // radius, radius, length
  CHECK(LowestZ(tube, PitchedAt({0.0, 0.0, 0.5}, 0.0)) == Approx(0.5 - 0.16).margin(1e-12));
  const double tilt = 30.0 * M_PI / 180.0;
  CHECK(LowestZ(tube, PitchedAt({0.0, 0.0, 0.5}, tilt)) == Approx(0.5 - 0.16 * std::cos(tilt) - 0.015 * std::sin(tilt)).margin(1e-12));
  CHECK(LowestZ(tube, PitchedAt({0.0, 0.0, 0.5}, M_PI / 2)) == Approx(0.5 - 0.015).margin(1e-12));
}

TEST_CASE("LowestZ: a sphere's bottom whatever its orientation", "[collision_shape]") {
  const CollisionShape ball = BareShape(ShapeType::kSphere, Eigen::Vector3d::Constant(0.031));
  CHECK(LowestZ(ball, PitchedAt({0.3, 0.1, 0.2}, 0.7)) == Approx(0.2 - 0.031).margin(1e-12));
}
