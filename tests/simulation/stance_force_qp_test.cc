// The executor's stance-force distribution: weight shared, the moments of the forces along the
// ground balanced by the normal forces, friction pyramids, swing feet and motor room respected.
#include <catch2/catch.hpp>

#include "stairplan/simulation/body_reference.h"
#include "stairplan/simulation/stance_force_qp.h"

using namespace stairplan;

namespace {

constexpr double kMass = 30.0;
constexpr double kG = 9.81;

std::array<StanceForceQp::Foot, 4> SquareStance() {
  std::array<StanceForceQp::Foot, 4> feet;
  const double xs[4] = {0.3, 0.3, -0.3, -0.3}, ys[4] = {0.18, -0.18, 0.18, -0.18};
  for (int i = 0; i < 4; ++i) {
    feet[static_cast<std::size_t>(i)].position_W = {xs[i], ys[i], 0.0};
    feet[static_cast<std::size_t>(i)].max_normal = 3 * kMass * kG;
  }
  return feet;
}

Eigen::Matrix<double, 6, 1> Wrench(const std::array<StanceForceQp::Foot, 4>& feet, const std::array<Eigen::Vector3d, 4>& f,
                                   const Eigen::Vector3d& com) {
  Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    w.head<3>() += f[i];
    w.tail<3>() += (feet[i].position_W - com).cross(f[i]);
  }
  return w;
}

}  // namespace

TEST_CASE("standing still, four feet share the weight", "[simulation]") {
  StanceForceQp qp;
  const auto feet = SquareStance();
  std::array<Eigen::Vector3d, 4> f;
  const Eigen::Vector3d com(0, 0, 0.4);
  REQUIRE(qp.Solve(feet, com, {0, 0, kMass * kG}, Eigen::Vector3d::Zero(), f));
  for (const Eigen::Vector3d& fi : f) {
    CHECK(fi.z() == Approx(kMass * kG / 4).epsilon(1e-3));
    CHECK(fi.head<2>().norm() < 1e-3);
  }
}

TEST_CASE("accelerating sideways, the feet on the far side push harder so that the body does not roll",
          "[simulation]") {
  StanceForceQp qp;
  const auto feet = SquareStance();
  std::array<Eigen::Vector3d, 4> f;
  const Eigen::Vector3d com(0, 0, 0.4);
  const Eigen::Vector3d force(0, kMass * 2.0, kMass * kG);  // 2 m/s^2 to the left
  REQUIRE(qp.Solve(feet, com, force, Eigen::Vector3d::Zero(), f));
  const Eigen::Matrix<double, 6, 1> w = Wrench(feet, f, com);
  CHECK((w.head<3>() - force).norm() < 1e-2 * force.norm());
  CHECK(w.tail<3>().norm() < 0.05);  // no roll moment although the ground pushes sideways 0.4 m below the COM
  // Sum y_i fz_i = -0.4 m * 2 m/s^2 * mass: the right feet (y < 0) carry more.
  CHECK(f[1].z() + f[3].z() > f[0].z() + f[2].z() + 100.0);
  for (const Eigen::Vector3d& fi : f) {
    CHECK(fi.z() > 0.0);
    CHECK(std::abs(fi.x()) <= 0.7 * 0.8 * fi.z() + 1e-6);
    CHECK(std::abs(fi.y()) <= 0.7 * 0.8 * fi.z() + 1e-6);
  }
}

TEST_CASE("a swinging foot carries nothing and motors are not asked for more than they have", "[simulation]") {
  StanceForceQp qp;
  auto feet = SquareStance();
  feet[3].max_normal = 0.0;  // RH swings
  std::array<Eigen::Vector3d, 4> f;
  // The COM over the LF-RF-LH triangle's centroid.
  const Eigen::Vector3d com(0.1, 0.06, 0.4);
  REQUIRE(qp.Solve(feet, com, {0, 0, kMass * kG}, Eigen::Vector3d::Zero(), f));
  CHECK(f[3].norm() < 1e-9);
  CHECK(f[0].z() + f[1].z() + f[2].z() == Approx(kMass * kG).epsilon(1e-3));
  // Now LF's motor may only give 50 N of push (torque map: identity, room [-50, 50]).
  feet[0].torque_map = Eigen::Matrix3d::Identity();
  feet[0].torque_lo = Eigen::Vector3d::Constant(-50.0);
  feet[0].torque_hi = Eigen::Vector3d::Constant(50.0);
  REQUIRE(qp.Solve(feet, com, {0, 0, kMass * kG}, Eigen::Vector3d::Zero(), f));
  CHECK(f[0].z() <= 50.0 + 1e-6);
  CHECK(f[3].norm() < 1e-9);
}

TEST_CASE("stance-force settings name the offending field", "[simulation]") {
  StanceForceSettings s;
  s.friction_use = 1.5;
  CHECK_THROWS_WITH(s.Validate(), Catch::Contains("friction_use"));
  s = StanceForceSettings{};
  s.torque_use = -0.1;
  CHECK_THROWS_WITH(StanceForceQp(s), Catch::Contains("torque_use"));
}

TEST_CASE("the body reference passes through the plan's samples with their velocity and acceleration",
          "[simulation]") {
  std::vector<BodyState> body;
  for (int k = 0; k <= 20; ++k) {
    BodyState b;
    b.t = 0.05 * k;
    b.x = 0.3 * b.t;                 // constant 0.3 m/s
    b.y = 0.5 * b.t * b.t;           // constant 1 m/s^2
    b.z = 0.4;
    b.pitch = -0.1 * b.t;
    body.push_back(b);
  }
  for (int k = 2; k <= 18; ++k) {
    const BodyReferenceState at = BodyReferenceAt(body, 0.05 * k);
    CHECK(at.pose.position_W.x() == Approx(0.3 * 0.05 * k));
    CHECK(at.velocity_W.x() == Approx(0.3));
    CHECK(at.velocity_W.y() == Approx(0.05 * k).margin(1e-9));
    CHECK(at.pitch_rate == Approx(-0.1));
    const BodyReferenceState mid = BodyReferenceAt(body, 0.05 * k + 0.025);
    CHECK(mid.acceleration_W.y() == Approx(1.0).margin(1e-6));
    CHECK(mid.acceleration_W.x() == Approx(0.0).margin(1e-9));
  }
  // At rest before and after the plan.
  CHECK(BodyReferenceAt(body, -1.0).velocity_W.norm() == 0.0);
  CHECK(BodyReferenceAt(body, 5.0).pose.position_W.x() == Approx(0.3));
}
