// The validator's dynamic check: contact forces in friction pyramids within the effort limits must
// produce the body's motion. A hand-built stance with a known answer, the quasi-static agreement
// with the support polygon, and the default plan against planted infeasible versions of it.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <string>

#include "stairplan/geometry/shapes.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/validation/contact_wrench_check.h"
#include "stairplan/planning/validation/contact_wrench_qp.h"
#include "stairplan/planning/validation/traversal_validator.h"
#include "nominal_stance.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

constexpr double kMass = 30.0;
constexpr double kG = 9.81;

// Four feet on flat ground at the corners of a 0.6 m x 0.3 m rectangle around the origin, no torque
// limits unless given.
std::array<WrenchFoot, 4> FlatStance() {
  std::array<WrenchFoot, 4> feet;
  const double xs[4] = {0.3, 0.3, -0.3, -0.3}, ys[4] = {0.15, -0.15, 0.15, -0.15};
  for (std::size_t i = 0; i < 4; ++i) {
    feet[i].stance = true;
    feet[i].position_W = {xs[i], ys[i], 0.0};
  }
  return feet;
}

WrenchDemand Standing(const Eigen::Vector3d& com, const Eigen::Vector3d& acceleration = Eigen::Vector3d::Zero()) {
  WrenchDemand d;
  d.com_W = com;
  d.force_W = kMass * (acceleration + Eigen::Vector3d(0, 0, kG));
  return d;
}

std::string DescribeDynamics(const ValidationReport& r) {
  std::string text = "dynamics: max residual " + std::to_string(r.dynamics.max_residual_n) + " N at t=" +
                     std::to_string(r.dynamics.max_residual_t) + ", tolerance " + std::to_string(r.dynamics.tolerance_n) +
                     " N, failed instants " + std::to_string(r.dynamics.failed_instants) + ", violations:";
  for (const Violation& v : r.violations) {
    text += "\n  t=" + std::to_string(v.t) + " " + v.leg + " " + ToString(v.kind) + " " + std::to_string(v.value) + " " + v.detail;
  }
  return text;
}

// The first dynamics violation, or nullptr.
const Violation* FirstDynamicsViolation(const ValidationReport& r) {
  for (const Violation& v : r.violations) {
    if (FamilyOf(v.kind) == CheckFamily::kDynamics) return &v;
  }
  return nullptr;
}

// The same footsteps and body path with every time multiplied by `scale` (0.5: twice the pace, the
// body's accelerations four times as large).
Plan TimeScaled(Plan plan, double scale) {
  for (BodyState& b : plan.body) b.t *= scale;
  for (Footstep& f : plan.footsteps) {
    f.t_liftoff *= scale;
    f.t_touchdown *= scale;
  }
  plan.cadence_s *= scale;
  return plan;
}

ValidationSettings Judging() {
  ValidationSettings settings;
  settings.dynamics.mode = DynamicsCheckMode::kJudge;
  return settings;
}

// The default climb; under the sanitizers (a quarter minute a 7-step plan) 3 of its steps.
StairSpec DynamicsClimbSpec() {
  StairSpec spec;
  spec.steps = testing::FullOrSanitized(spec.steps, 3);
  return spec;
}

struct DynamicsClimbPlan {
  Staircase stairs{DynamicsClimbSpec()};
  PipelineResult result = RunPipeline(BuiltinRobot(), stairs, PipelineOptions{});
  ValidationReport Validate(const Plan& plan, const ValidationSettings& settings = {}) {
    TraversalValidator validator(BuiltinRobot(), stairs, result.map, settings);
    return validator.Validate(plan);
  }
};

DynamicsClimbPlan& DynamicsClimb() {
  static DynamicsClimbPlan plan;
  return plan;
}

}  // namespace

TEST_CASE("four feet on flat ground carry a centred COM equally with no residual", "[dynamics]") {
  ContactWrenchQp qp(kMass, 0.3);
  const WrenchResult& r = qp.Solve(FlatStance(), Standing({0.0, 0.0, 0.4}));
  REQUIRE(r.solved);
  CHECK(r.within_tolerance);
  CHECK(r.residual < 1e-6 * kMass * kG);
  CHECK(r.limit == WrenchLimit::kNone);
  for (const Eigen::Vector3d& f : r.forces_W) {
    CHECK(f.z() == Approx(kMass * kG / 4).epsilon(1e-6));
    CHECK(f.head<2>().norm() < 1e-6);
  }
}

TEST_CASE("a static COM fails the dynamic check exactly when it leaves the support polygon", "[dynamics]") {
  ContactWrenchQp qp(kMass, 0.3);
  SECTION("four feet") {
    const std::array<WrenchFoot, 4> feet = FlatStance();
    const Polygon2 hull = ConvexHull({{0.3, 0.15}, {0.3, -0.15}, {-0.3, 0.15}, {-0.3, -0.15}});
    for (double x = -0.5; x <= 0.5; x += 0.02) {
      const Eigen::Vector2d com(x, 0.07);
      const double margin = -hull.SignedDistance(com);
      if (std::abs(margin) < 1e-3) continue;  // on the edge either answer is right
      const WrenchResult& r = qp.Solve(feet, Standing({com.x(), com.y(), 0.4}));
      INFO("COM x " << x << ", margin " << margin << ", residual " << r.residual);
      CHECK(r.within_tolerance == (margin > 0.0));
      if (margin < 0.0) {
        CHECK(r.limit == WrenchLimit::kWrenchUnattainable);
        CHECK(r.leg != LegId::kNone);
      }
    }
  }
  SECTION("three feet, the front right swinging: the COM beyond the diagonal fails, and the hind foot opposite would have to pull") {
    std::array<WrenchFoot, 4> feet = FlatStance();
    feet[1].stance = false;
    CHECK(qp.Solve(feet, Standing({-0.05, 0.0, 0.4})).within_tolerance);  // on the left of the LF-RH diagonal
    const WrenchResult& r = qp.Solve(feet, Standing({0.05, -0.05, 0.4}));  // right of it
    CHECK_FALSE(r.within_tolerance);
    CHECK(r.limit == WrenchLimit::kWrenchUnattainable);
    CHECK(r.leg == LegId::kLeftHind);
    CHECK(r.forces_W[1].norm() < 1e-9);  // the swinging foot carries nothing
  }
}

TEST_CASE("a sideways push beyond the friction pyramid names the friction cone, a weak motor the torque limit", "[dynamics]") {
  ContactWrenchQp qp(kMass, 0.3, [] {
    ContactWrenchSettings s;
    s.friction = 0.3;
    return s;
  }());
  const Eigen::Vector3d com(0.0, 0.0, 0.4);
  // 0.2 g forward needs a friction coefficient of 0.2 only.
  CHECK(qp.Solve(FlatStance(), Standing(com, {0.2 * kG, 0.0, 0.0})).within_tolerance);
  const WrenchResult& slip = qp.Solve(FlatStance(), Standing(com, {0.5 * kG, 0.0, 0.0}));
  CHECK_FALSE(slip.within_tolerance);
  CHECK(slip.limit == WrenchLimit::kFrictionCone);
  CHECK(slip.leg != LegId::kNone);
  // The inscribed pyramid gives mu' = mu cos(pi/8) of the normal force forward; the least squared
  // residual trades a push d beyond the weight for mu' d more grip: of the forward deficit
  // D = m a - mu' m g it leaves D / sqrt(1 + mu'^2).
  const double mu = 0.3 * std::cos(3.14159265358979 / 8);
  CHECK(slip.residual == Approx(kMass * kG * (0.5 - mu) / std::sqrt(1 + mu * mu)).epsilon(1e-6));

  std::array<WrenchFoot, 4> weak = FlatStance();
  for (WrenchFoot& f : weak) {
    f.torque_map = 0.2 * Eigen::Matrix3d::Identity();  // a 0.2 m lever in every direction
    f.effort = Eigen::Vector3d::Constant(30.0);        // up to 150 N of normal force per foot
  }
  weak[3].effort.z() = 5.0;  // RH holds only 25 N: the others must carry the rest, which they can
  CHECK(qp.Solve(weak, Standing(com)).within_tolerance);
  const WrenchResult& heavy = qp.Solve(weak, Standing(com, {0.0, 0.0, 0.8 * kG}));  // 530 N for 475 N of motors
  CHECK_FALSE(heavy.within_tolerance);
  CHECK(heavy.limit == WrenchLimit::kTorqueLimit);
}

TEST_CASE("a robot whose URDF has no effort limits is checked without torque rows, and says so", "[dynamics]") {
  const RobotModel limited = BuiltinRobot();
  const RobotModel unlimited = RobotModel::FromUrdfString(
      std::regex_replace(BuiltinRobotUrdf(), std::regex("effort=\"[0-9.]+\""), "effort=\"0\""), "stairbot without efforts");
  const RobotKinematics with(limited), without(unlimited);
  RobotWorkspace ws_with(with), ws_without(without);
  ContactWrenchCheck check_with(with, limited.total_mass()), check_without(without, unlimited.total_mass());
  CHECK(check_with.torque_limits_checked());
  CHECK_FALSE(check_without.torque_limits_checked());
  CHECK(check_with.body_inertia_known());
  // Standing on the nominal stance under a 5 g upward push: the motors cannot, unlimited ones can.
  WrenchInstant instant = testing::NominalStance(with, ws_with);
  instant.rates.linear_W = {0.0, 0.0, 5 * kG};
  const WrenchResult& r_with = check_with.Check(instant, ws_with);
  CHECK_FALSE(r_with.within_tolerance);
  CHECK(r_with.limit == WrenchLimit::kTorqueLimit);
  CHECK(check_without.Check(instant, ws_without).within_tolerance);
  instant.rates.linear_W.setZero();
  CHECK(check_with.Check(instant, ws_with).within_tolerance);
}

TEST_CASE("the contact-wrench QP rejects bad settings and inputs by name", "[dynamics]") {
  ContactWrenchSettings s;
  s.friction_faces = 3;
  CHECK_THROWS_WITH(ContactWrenchQp(kMass, 0.3, s), Catch::Contains("friction_faces"));
  ContactWrenchQp qp(kMass, 0.3);
  std::array<WrenchFoot, 4> feet = FlatStance();
  feet[2].position_W.x() = std::nan("");
  CHECK_THROWS_WITH(qp.Solve(feet, Standing({0, 0, 0.4})), Catch::Contains("LH"));
  ValidationSettings v;
  CHECK_THROWS_WITH(v.Set("frictoin", 0.5), Catch::Contains("frictoin"));
  v.Set("friction", 0.5);
  CHECK(v.dynamics.friction == 0.5);
}

TEST_CASE("the default plan is dynamically feasible and planted infeasible versions of it are caught", "[dynamics][validator]") {
  DynamicsClimbPlan& s = DynamicsClimb();
  REQUIRE(s.result.plan.status == PlanStatus::kOk);

  SECTION("the default plan passes the dynamic check") {
    const ValidationReport r = s.Validate(s.result.plan, Judging());
    INFO(DescribeDynamics(r));
    INFO("default plan: max wrench residual " << r.dynamics.max_residual_n << " N at t=" << r.dynamics.max_residual_t
                                              << " s (tolerance " << r.dynamics.tolerance_n << " N)");
    CHECK(r.dynamics.mode == DynamicsCheckMode::kJudge);
    CHECK(r.dynamics.torque_limits_checked);
    CHECK(r.dynamics.body_inertia_known);
    CHECK(r.dynamics.failed_instants == 0);
    CHECK(FirstDynamicsViolation(r) == nullptr);
    CHECK(r.ok);
  }

  SECTION("the same footsteps at twice the pace fail with the instant and a leg named") {
    const ValidationReport r = s.Validate(TimeScaled(s.result.plan, 0.5), Judging());
    INFO(DescribeDynamics(r));
    const Violation* v = FirstDynamicsViolation(r);
    REQUIRE(v != nullptr);
    INFO("twice the pace: first dynamics violation at t=" << v->t << " s, " << v->leg << ", " << ToString(v->kind) << ", residual "
                                                         << v->value << " N; " << r.dynamics.failed_instants << " instants fail");
    CHECK_FALSE(r.ok);
    CHECK(v->leg_id != LegId::kNone);
    CHECK(v->t > 0.0);
    CHECK(v->t < s.result.plan.duration() * 0.5);
    CHECK(v->value > r.dynamics.tolerance_n);
    CHECK(r.dynamics.first_failure_t == v->t);
    CHECK(r.dynamics.first_failure_leg == v->leg_id);
  }

  SECTION("a friction coefficient of 0.1 fails the default plan") {
    ValidationSettings settings = Judging();
    settings.dynamics.friction = 0.1;
    const ValidationReport r = s.Validate(s.result.plan, settings);
    INFO(DescribeDynamics(r));
    const Violation* v = FirstDynamicsViolation(r);
    REQUIRE(v != nullptr);
    INFO("friction 0.1: first dynamics violation at t=" << v->t << " s, " << v->leg << ", " << ToString(v->kind)
                                                       << ", residual " << v->value << " N");
    CHECK_FALSE(r.ok);
    CHECK(v->kind == ViolationKind::kFrictionCone);
    CHECK(v->leg_id != LegId::kNone);
  }

  SECTION("the default plan's body moved sideways off its feet fails both the stability and the dynamic check") {
    Plan plan = s.result.plan;
    for (BodyState& b : plan.body) b.y += 0.25;  // a constant offset: the accelerations stay as planned
    const ValidationReport r = s.Validate(plan, Judging());
    INFO(DescribeDynamics(r));
    const Violation* v = FirstDynamicsViolation(r);
    REQUIRE(v != nullptr);
    CHECK(v->kind == ViolationKind::kWrenchUnattainable);
    bool unstable = false;
    for (const Violation& w : r.violations) unstable = unstable || w.kind == ViolationKind::kStability;
    CHECK(unstable);
  }

  SECTION("reported by default, not judged: a planted failure is summarised but leaves the verdict alone") {
    ValidationSettings settings;
    CHECK(settings.dynamics.mode == DynamicsCheckMode::kReport);
    settings.dynamics.friction = 0.1;
    const ValidationReport r = s.Validate(s.result.plan, settings);
    INFO(DescribeDynamics(r));
    CHECK(r.ok);
    CHECK(FirstDynamicsViolation(r) == nullptr);
    CHECK(r.dynamics.failed_instants > 0);
    CHECK(r.dynamics.first_failure_kind == ViolationKind::kFrictionCone);
    CHECK(r.dynamics.first_failure_leg != LegId::kNone);
    settings.dynamics.mode = DynamicsCheckMode::kOff;
    const ValidationReport off = s.Validate(s.result.plan, settings);
    CHECK(off.dynamics.failed_instants == 0);
    CHECK(off.dynamics.max_residual_n == 0.0);
  }
}

TEST_CASE("two feet: the moment about their line leaves the wrench, with the body's inertia and toppling about it",
          "[dynamics]") {
  const RobotModel robot = BuiltinRobot();
  const RobotKinematics kinematics(robot);
  RobotWorkspace ws(kinematics);
  ContactWrenchCheck check(kinematics, kMass);
  // LF and RH stand on the ground; the COM 0.4 m above the middle of their line, `offset` to the
  // left of it (perpendicular), at rest.
  WrenchInstant instant;
  instant.body.position_W = {0.0, 0.0, 0.4};
  instant.feet_W = {Eigen::Vector3d(0.3, 0.15, 0), Eigen::Vector3d(0.3, -0.15, 0), Eigen::Vector3d(-0.3, 0.15, 0),
                    Eigen::Vector3d(-0.3, -0.15, 0)};
  instant.normals_W.fill(Eigen::Vector3d::UnitZ());
  instant.stance = {true, false, false, true};
  for (std::size_t l = 0; l < 4; ++l) instant.q[l] = kinematics.leg(static_cast<int>(l)).nominal();
  const Eigen::Vector3d along = (instant.feet_W[3] - instant.feet_W[0]).normalized();
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(along);
  for (const double offset : {0.0, 0.02}) {
    CAPTURE(offset);
    instant.com_W = Eigen::Vector3d(0, 0, 0.4) + offset * across;
    const WrenchResult& r = check.Check(instant, ws);
    const LineSupport& line = check.line();
    REQUIRE(line.active);
    CHECK(line.pair == (1 | 8));
    // The weight's moment about the line, m g times the COM's distance from it, is the line's;
    // what is left the two feet carry exactly.
    CHECK(std::abs(line.moment) == Approx(kMass * kG * offset).margin(1e-9));
    CHECK(r.residual < 1e-3);
    // Toppling about the line: m g h per radian; the inertia at least m h^2.
    CHECK(line.stiffness == Approx(kMass * kG * 0.4).epsilon(0.01));
    CHECK(line.inertia >= kMass * 0.4 * 0.4);
  }
  instant.stance = {true, true, true, false};
  check.Check(instant, ws);
  CHECK_FALSE(check.line().active);
}
