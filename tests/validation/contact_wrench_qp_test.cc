// The dynamic check's per-instant QP (planning/validation/contact_wrench_qp.h): on level feet with
// only the weight to carry it is the support-polygon test; beyond the friction pyramid, the effort
// limits or the span of the feet it misses the wrench and names what limits it; and it allocates
// nothing after its first solve.
#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Geometry>

#include "alloc_counter.h"
#include "geometry/shapes.h"
#include "planning/validation/contact_wrench_qp.h"

using namespace stairplan;

namespace {

constexpr double kMass = 10.0;
constexpr double kWeight = kMass * 9.81;

std::array<ContactFoot, 4> SquareFeet(double half) {
  std::array<ContactFoot, 4> feet;
  const double xs[] = {half, half, -half, -half}, ys[] = {half, -half, half, -half};
  for (std::size_t i = 0; i < 4; ++i) {
    feet[i].stance = true;
    feet[i].position_W = Eigen::Vector3d(xs[i], ys[i], 0.0);
    feet[i].torque_map = 0.2 * Eigen::Matrix3d::Identity();
  }
  return feet;
}

}  // namespace

TEST_CASE("with only the weight on level feet, the contact QP is the support-polygon test", "[contact_wrench]") {
  ContactWrenchQp qp;
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> coord(-0.3, 0.3);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::array<ContactFoot, 4> feet;
    std::vector<Eigen::Vector2d> support;
    const int down = 3 + trial % 2;
    for (int i = 0; i < 4; ++i) {
      ContactFoot& foot = feet[static_cast<std::size_t>(i)];
      foot.stance = i < down;
      foot.position_W = Eigen::Vector3d(coord(rng), coord(rng), 0.0);
      if (foot.stance) support.push_back(foot.position_W.head<2>());
    }
    const Eigen::Vector3d com(0.7 * coord(rng), 0.7 * coord(rng), 0.35);
    const double margin = -ConvexHull(support).SignedDistance(com.head<2>());
    if (std::abs(margin) < 2e-3) continue;  // on the edge: either answer is a rounding
    const ContactWrenchResult& r = qp.Solve(feet, com, Eigen::Vector3d(0, 0, kWeight), Eigen::Vector3d::Zero());
    CAPTURE(trial, margin, r.residual, ToString(r.limit));
    if (margin > 0.0) {
      ++inside;
      CHECK(r.residual < 1e-3 * kWeight);
      CHECK(r.limit == ContactLimit::kNone);
      // The forces push, carry the weight and have no moment about the COM.
      Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < 4; ++i) {
        CHECK(r.forces_W[i].z() >= -1e-9);
        if (!feet[i].stance) CHECK(r.forces_W[i].norm() < 1e-9);
        force += r.forces_W[i];
        moment += (feet[i].position_W - com).cross(r.forces_W[i]);
      }
      CHECK((force - Eigen::Vector3d(0, 0, kWeight)).norm() < 1e-2);
      CHECK(moment.norm() < 1e-2);
    } else {
      ++outside;
      // Outside by d, the weight's moment about the polygon's edge is at least W d: some of it
      // is missed, force or moment.
      CHECK(r.residual > 0.05 * kWeight * std::min(1.0, -margin / qp.settings().moment_lever));
      // What limits it: a foot that would have to pull, one that would slip (far out, where the
      // QP trades the weight's moment against horizontal forces below the COM), or, where random
      // feet fall in a line, the line's geometry.
      CHECK(r.limit != ContactLimit::kNone);
      CHECK(r.limit != ContactLimit::kNotSolved);
      if (r.limit == ContactLimit::kPull || r.limit == ContactLimit::kFriction) {
        REQUIRE(r.foot >= 0);
        CHECK(feet[static_cast<std::size_t>(r.foot)].stance);
      }
    }
  }
  CHECK(inside > 50);
  CHECK(outside > 50);
}

TEST_CASE("the contact QP misses a horizontal push beyond the friction pyramid and names friction", "[contact_wrench]") {
  ContactWrenchSettings settings;
  settings.friction = 0.5;
  ContactWrenchQp qp(settings);
  const std::array<ContactFoot, 4> feet = SquareFeet(0.2);
  const Eigen::Vector3d com(0.0, 0.0, 0.0);  // level with the feet: a push has no moment about it
  const double limit = settings.friction / std::sqrt(2.0);  // the inscribed pyramid's slope
  const auto push = [&](double share) {
    return qp.Solve(feet, com, Eigen::Vector3d(share * kWeight, 0.0, kWeight), Eigen::Vector3d::Zero());
  };
  const ContactWrenchResult within = push(0.95 * limit);
  CHECK(within.residual < 1e-3 * kWeight);
  CHECK(within.limit == ContactLimit::kNone);
  const ContactWrenchResult beyond = push(1.2 * limit);
  CHECK(beyond.limit == ContactLimit::kFriction);
  CHECK(beyond.foot >= 0);
  // All four feet at the pyramid's edge give slope * weight; the QP may trade some weight for
  // push, so it misses no more than the excess.
  CHECK(beyond.residual > 0.01 * kWeight);
  CHECK(beyond.residual <= 0.2 * limit * kWeight + 1e-6);
}

TEST_CASE("the contact QP misses the weight when the joints' effort limits are too low and names the joint", "[contact_wrench]") {
  ContactWrenchQp qp;
  std::array<ContactFoot, 4> feet = SquareFeet(0.2);
  for (ContactFoot& foot : feet) foot.effort = Eigen::Vector3d(50.0, 50.0, 2.0);  // 0.2 m x 10 N per foot
  const ContactWrenchResult& r = qp.Solve(feet, Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0, 0, kWeight), Eigen::Vector3d::Zero());
  CHECK(r.limit == ContactLimit::kTorque);
  CHECK(r.joint == 2);
  CHECK(r.foot >= 0);
  // Four feet give 40 N of the 98.1 N weight at most.
  CHECK(r.residual == Approx(kWeight - 40.0).margin(0.5));
}

TEST_CASE("two feet cannot hold a centre of mass off the line between them: the geometry limits", "[contact_wrench]") {
  ContactWrenchQp qp;
  std::array<ContactFoot, 4> feet = SquareFeet(0.2);
  feet[1].stance = false;  // a trot's diagonal pair: LF and RH down
  feet[2].stance = false;
  const ContactWrenchResult& on_line = qp.Solve(feet, Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0, 0, kWeight), Eigen::Vector3d::Zero());
  CHECK(on_line.residual < 1e-3 * kWeight);
  const ContactWrenchResult& off = qp.Solve(feet, Eigen::Vector3d(0.05, -0.05, 0.3), Eigen::Vector3d(0, 0, kWeight), Eigen::Vector3d::Zero());
  CHECK(off.residual > 0.05 * kWeight);
  CHECK(off.limit == ContactLimit::kGeometry);
  CHECK(off.foot == -1);
  CHECK(off.forces_W[1].norm() < 1e-9);
  CHECK(off.forces_W[2].norm() < 1e-9);
}

TEST_CASE("the contact QP allocates nothing after its first solve", "[contact_wrench][alloc]") {
  ContactWrenchQp qp;
  std::array<ContactFoot, 4> feet = SquareFeet(0.2);
  qp.Solve(feet, Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0, 0, kWeight), Eigen::Vector3d::Zero());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.1, 0.1);
  testing::AllocationScope scope;
  double total = 0.0;
  for (int k = 0; k < 200; ++k) {
    for (std::size_t i = 0; i < 4; ++i) feet[i].stance = (k + static_cast<int>(i)) % 4 != 0;
    const Eigen::Vector3d com(shift(rng), shift(rng), 0.3);
    total += qp.Solve(feet, com, Eigen::Vector3d(shift(rng) * kWeight, 0.0, kWeight), Eigen::Vector3d(0, shift(rng), 0)).residual;
  }
  CHECK(scope.count() == 0u);
  CHECK(std::isfinite(total));
}
