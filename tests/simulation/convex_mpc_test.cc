// The executor's convex MPC: its condensed dynamics against a step-by-step simulation of the same
// linear model, its forces inside their pyramids and at zero in the air, and the balance it finds
// standing still and the push it gives toward a reference ahead.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "stairplan/simulation/convex_mpc.h"
#include "stairplan/simulation/sim_settings.h"

using namespace stairplan;

namespace {

constexpr double kMpcMass = 30.0, kMpcG = 9.81;

// A body at rest 0.4 m above four feet at the corners of a 0.6 x 0.36 m rectangle, the reference
// standing still there; `air` lifts the feet whose mask bit is set at every knot after the first.
std::vector<MpcKnot> StandingKnots(const ConvexMpcSettings& settings, unsigned air = 0) {
  std::vector<MpcKnot> knots(static_cast<std::size_t>(settings.knots));
  const std::array<Eigen::Vector3d, 4> feet = {Eigen::Vector3d(0.3, 0.18, 0), Eigen::Vector3d(0.3, -0.18, 0),
                                               Eigen::Vector3d(-0.3, 0.18, 0), Eigen::Vector3d(-0.3, -0.18, 0)};
  for (std::size_t k = 0; k < knots.size(); ++k) {
    MpcKnot& knot = knots[k];
    knot.position_W = Eigen::Vector3d(0, 0, 0.4);
    knot.inertia_W = Eigen::Vector3d(0.3, 0.8, 0.9).asDiagonal();
    knot.feet_W = feet;
    for (std::size_t i = 0; i < 4; ++i) knot.max_normal[i] = k > 0 && (air >> i & 1u) ? 0.0 : 3.0 * kMpcMass * kMpcG;
  }
  return knots;
}

MpcState StandingState() {
  MpcState state;
  state.position_W = Eigen::Vector3d(0, 0, 0.4);
  return state;
}

}  // namespace

TEST_CASE("convex MPC: standing on four feet at the reference, the feet carry the weight and the body stays put",
          "[simulation][mpc]") {
  const ConvexMpcSettings settings;
  ConvexMpc mpc(kMpcMass, settings);
  const std::vector<MpcKnot> knots = StandingKnots(settings);
  std::array<Eigen::Vector3d, 4> forces;
  REQUIRE(mpc.Solve(StandingState(), knots.data(), MpcMotors{}, forces));
  Eigen::Vector3d total = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    total += forces[i];
    moment += (knots[0].feet_W[i] - knots[0].position_W).cross(forces[i]);
  }
  CHECK(total.x() == Approx(0.0).margin(1e-3 * kMpcMass * kMpcG));
  CHECK(total.y() == Approx(0.0).margin(1e-3 * kMpcMass * kMpcG));
  CHECK(total.z() == Approx(kMpcMass * kMpcG).epsilon(1e-3));
  CHECK(moment.norm() < 1e-2);
  for (int k = 1; k <= settings.knots; ++k) {
    const Eigen::Matrix<double, 12, 1> x = mpc.Predicted(k);
    CAPTURE(k);
    CHECK((x.segment<3>(3) - knots[0].position_W).norm() < 1e-3);  // position
    CHECK(x.segment<3>(0).norm() < 1e-3);                             // attitude error
  }
}

TEST_CASE("convex MPC: the condensed prediction is the linear model stepped knot by knot with the solved forces",
          "[simulation][mpc]") {
  ConvexMpcSettings settings;
  ConvexMpc mpc(kMpcMass, settings);
  // A trot's diagonal: LF and RH stand after the first knot, the body displaced and turning.
  std::vector<MpcKnot> knots = StandingKnots(settings, 0b0110u);
  for (std::size_t k = 0; k < knots.size(); ++k) {
    knots[k].position_W += Eigen::Vector3d(0.02 * static_cast<double>(k), 0, 0);
    knots[k].velocity_W = Eigen::Vector3d(0.5, 0, 0);
  }
  MpcState state = StandingState();
  state.position_W += Eigen::Vector3d(-0.01, 0.015, 0.005);
  state.attitude_error_W = Eigen::Vector3d(0.03, -0.02, 0.01);
  state.velocity_W = Eigen::Vector3d(0.4, -0.05, 0.02);
  state.angular_velocity_W = Eigen::Vector3d(0.2, 0.1, -0.1);
  std::array<Eigen::Vector3d, 4> first;
  REQUIRE(mpc.Solve(state, knots.data(), MpcMotors{}, first));
  // Step the model: x+ = A x + B(knot) u + d with the forces the QP chose.
  const double dt = settings.knot_dt, half = 0.5 * dt * dt;
  Eigen::Vector3d e = state.attitude_error_W, p = state.position_W, w = state.angular_velocity_W, v = state.velocity_W;
  const Eigen::Vector3d g(0, 0, -kMpcG);
  for (int k = 0; k < settings.knots; ++k) {
    const MpcKnot& knot = knots[static_cast<std::size_t>(k)];
    const std::array<Eigen::Vector3d, 4> f = mpc.Forces(k);
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    const double mu = settings.friction_use * settings.friction;
    for (std::size_t i = 0; i < 4; ++i) {
      CAPTURE(k, i);
      if (!(knot.max_normal[i] > 0.0)) CHECK(f[i].norm() < 1e-9);
      CHECK(std::abs(f[i].x()) <= mu * f[i].z() + 1e-6);
      CHECK(std::abs(f[i].y()) <= mu * f[i].z() + 1e-6);
      CHECK(f[i].z() >= -1e-9);
      force += f[i];
      torque += (knot.feet_W[i] - knot.position_W - knot.com_offset_W).cross(f[i]);
    }
    const Eigen::Vector3d alpha = knot.inertia_W.inverse() * torque, a = force / kMpcMass + g;
    e += dt * (w - knot.angular_velocity_W) + half * alpha;
    p += dt * v + half * a;
    w += dt * alpha;
    v += dt * a;
    const Eigen::Matrix<double, 12, 1> x = mpc.Predicted(k + 1);
    CAPTURE(k);
    CHECK((x.segment<3>(0) - e).norm() < 1e-9);
    CHECK((x.segment<3>(3) - p).norm() < 1e-9);
    CHECK((x.segment<3>(6) - w).norm() < 1e-9);
    CHECK((x.segment<3>(9) - v).norm() < 1e-9);
  }
  CHECK(first == mpc.Forces(0));
}

TEST_CASE("convex MPC: a reference ahead gets a push forward, one behind a push back", "[simulation][mpc]") {
  const ConvexMpcSettings settings;
  for (const double ahead : {0.05, -0.05}) {
    ConvexMpc mpc(kMpcMass, settings);
    std::vector<MpcKnot> knots = StandingKnots(settings);
    for (std::size_t k = 1; k < knots.size(); ++k) knots[k].position_W.x() += ahead;
    std::array<Eigen::Vector3d, 4> forces;
    REQUIRE(mpc.Solve(StandingState(), knots.data(), MpcMotors{}, forces));
    const double push = forces[0].x() + forces[1].x() + forces[2].x() + forces[3].x();
    CAPTURE(ahead, push);
    CHECK(push * ahead > 0.0);
  }
}

TEST_CASE("convex MPC: bad settings and masses are refused, naming the field", "[simulation][mpc]") {
  ConvexMpcSettings settings;
  settings.knots = 1;
  CHECK_THROWS_WITH(ConvexMpc(kMpcMass, settings), Catch::Contains("knots"));
  settings = {};
  settings.knot_dt = std::nan("");
  CHECK_THROWS_WITH(ConvexMpc(kMpcMass, settings), Catch::Contains("knot_dt"));
  CHECK_THROWS_WITH(ConvexMpc(0.0, ConvexMpcSettings{}), Catch::Contains("mass"));
  // Through the simulation's settings, named as `simulate --set` spells them.
  SimSettings sim;
  sim.Set("mpc.knot_dt", 0.0);
  CHECK_THROWS_WITH(sim.Validate(), Catch::Contains("mpc.knot_dt"));
  CHECK_THROWS_WITH(sim.Set("mpc.knots", 1.5), Catch::Contains("mpc.knots"));
}
