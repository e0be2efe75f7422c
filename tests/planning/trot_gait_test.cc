// The trot (GaitChoice::kTrot): the crawl's footholds with the diagonal pairs swinging together,
// and a body whose pendulum keeps its ZMP on the standing diagonal.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "stairplan/geometry/field_error.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/validation/traversal_validator.h"

using namespace stairplan;

namespace {

PipelineResult PlanTrotOrCrawl(TravelDirection direction, GaitChoice gait) {
  StairSpec spec;
  spec.direction = direction;
  PipelineOptions options;
  options.gait = gait;
  return RunPipeline(BuiltinRobot(), Staircase(spec), options);
}

// Each leg's footholds in time order.
std::map<std::string, std::vector<Eigen::Vector3d>> FootholdsByLeg(const Plan& plan) {
  std::map<std::string, std::vector<Eigen::Vector3d>> legs;
  for (const Footstep& f : plan.footsteps) legs[f.leg].push_back(f.position_W);
  return legs;
}

bool IsDiagonal(const std::string& a, const std::string& b) {
  return a[0] != b[0] && a[1] != b[1];  // "LF"/"RH": other side, other end
}

}  // namespace

TEST_CASE("trot: the crawl's footholds, each diagonal pair lifting and landing together, the default seven steps "
          "in under 8 s",
          "[pipeline][trot]") {
  for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
    CAPTURE(direction == TravelDirection::kUp ? "up" : "down");
    const PipelineResult crawl = PlanTrotOrCrawl(direction, GaitChoice::kCrawl);
    const PipelineResult trot = PlanTrotOrCrawl(direction, GaitChoice::kTrot);
    INFO(trot.plan.status_reason);
    REQUIRE(trot.plan.status == PlanStatus::kOk);
    REQUIRE(crawl.plan.status == PlanStatus::kOk);
    CHECK(trot.plan.gait == Gait::kTrot);
    CHECK(trot.plan.body_planner == BodyPlannerKind::kRecedingHorizonQp);
    // The same footholds leg by leg; only the timing pairs them.
    const auto trot_legs = FootholdsByLeg(trot.plan), crawl_legs = FootholdsByLeg(crawl.plan);
    REQUIRE(trot_legs.size() == 4);
    for (const auto& [leg, footholds] : trot_legs) {
      CAPTURE(leg);
      REQUIRE(footholds.size() == crawl_legs.at(leg).size());
      for (std::size_t i = 0; i < footholds.size(); ++i) CHECK((footholds[i] - crawl_legs.at(leg)[i]).norm() < 1e-12);
    }
    // Footsteps sorted by touchdown come in diagonal pairs sharing their liftoff and touchdown,
    // a four-feet phase of trot_shift_duration between one pair's touchdown and the next's liftoff.
    const PipelineOptions defaults;
    const std::vector<Footstep>& f = trot.plan.footsteps;
    REQUIRE(f.size() % 2 == 0);
    for (std::size_t i = 0; i + 1 < f.size(); i += 2) {
      CAPTURE(i, f[i].leg, f[i + 1].leg);
      CHECK(IsDiagonal(f[i].leg, f[i + 1].leg));
      CHECK(f[i].t_liftoff == Approx(f[i + 1].t_liftoff).margin(1e-9));
      CHECK(f[i].t_touchdown == Approx(f[i + 1].t_touchdown).margin(1e-9));
      CHECK(f[i].t_touchdown - f[i].t_liftoff == Approx(defaults.trot_swing_duration).margin(1e-9));
      if (i + 2 < f.size()) CHECK(f[i + 2].t_liftoff - f[i].t_touchdown == Approx(defaults.trot_shift_duration).margin(1e-9));
    }
    CHECK(FlightDuration(trot.plan) < 8.0);
    CHECK(FlightDuration(trot.plan) < 0.25 * FlightDuration(crawl.plan));
    // The trot's verdict includes the dynamic check.
    CHECK(trot.validation.dynamics.mode == DynamicsCheckMode::kJudge);
  }
}

TEST_CASE("trot: in two-foot support the body's pendulum keeps its ZMP near the standing diagonal", "[pipeline][trot]") {
  const PipelineResult trot = PlanTrotOrCrawl(TravelDirection::kUp, GaitChoice::kTrot);
  REQUIRE(trot.plan.status == PlanStatus::kOk);
  const Plan& plan = trot.plan;
  constexpr double kGravity = 9.81;
  std::vector<double> offsets;
  for (std::size_t i = 1; i + 1 < plan.body.size(); ++i) {
    const BodyState &a = plan.body[i - 1], &b = plan.body[i], &c = plan.body[i + 1];
    // Two feet standing through the three samples (a sample at a touchdown or liftoff has four).
    std::vector<bool> stance_a, stance_b, stance_c;
    const auto feet_a = FeetAt(plan.legs, plan.initial_feet_W, plan.footsteps, a.t, &stance_a);
    const auto feet_b = FeetAt(plan.legs, plan.initial_feet_W, plan.footsteps, b.t, &stance_b);
    const auto feet_c = FeetAt(plan.legs, plan.initial_feet_W, plan.footsteps, c.t, &stance_c);
    std::vector<Eigen::Vector3d> standing;
    for (std::size_t l = 0; l < plan.legs.size(); ++l) {
      if (stance_a[l] && stance_b[l] && stance_c[l] && (feet_a[l] - feet_c[l]).norm() < 1e-9) standing.push_back(feet_b[l]);
    }
    const auto count = [](const std::vector<bool>& stance) { return std::count(stance.begin(), stance.end(), true); };
    if (standing.size() != 2 || count(stance_a) != 2 || count(stance_b) != 2 || count(stance_c) != 2) continue;
    // The base as the pendulum's mass, as high above the feet's mean as it stands.
    const double dt = b.t - a.t;
    const Eigen::Vector2d p(b.x, b.y), acc = (Eigen::Vector2d(c.x, c.y) - 2.0 * p + Eigen::Vector2d(a.x, a.y)) / (dt * dt);
    const double height = b.z - 0.5 * (standing[0].z() + standing[1].z());
    const Eigen::Vector2d zmp = p - height / kGravity * acc;
    const Eigen::Vector2d along = (standing[1] - standing[0]).head<2>().normalized();
    offsets.push_back(std::abs(Eigen::Vector2d(along.y(), -along.x()).dot(zmp - standing[0].head<2>())));
  }
  REQUIRE(offsets.size() > 30);
  std::sort(offsets.begin(), offsets.end());
  const double median = offsets[offsets.size() / 2], p75 = offsets[offsets.size() * 3 / 4];
  CAPTURE(median, p75, offsets.back());
  // Without the diagonal's rows the ZMP wanders 6 cm from it on median.
  CHECK(median < 0.01);
  CHECK(p75 < 0.025);
}

TEST_CASE("trot: other footstep planners and bad durations are refused, naming the field", "[pipeline][trot]") {
  StairSpec spec;
  const Staircase stairs(spec);
  PipelineOptions options;
  options.gait = GaitChoice::kTrot;
  options.footsteps = FootstepSource::kStepPlanner;
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), stairs, options), Catch::Contains("gait"));
  options.footsteps = FootstepSource::kSelectedCrawl;
  options.trot_swing_duration = 0.0;
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), stairs, options), Catch::Contains("trot_swing_duration"));
  options.trot_swing_duration = 0.25;
  options.trot_shift_duration = std::nan("");
  CHECK_THROWS_WITH(RunPipeline(BuiltinRobot(), stairs, options), Catch::Contains("trot_shift_duration"));
  CHECK(ParseGaitChoice("trot") == GaitChoice::kTrot);
}

TEST_CASE("trot: on two feet the validator takes the moment about their line out of the wrench and judges the tilt "
          "it would cause",
          "[pipeline][trot][validation]") {
  // Down the default stairs the trot's body keeps its tilt under 0.03 rad in every two-foot phase,
  // and every other wrench is within the feet's reach: it validates.
  const PipelineResult down = PlanTrotOrCrawl(TravelDirection::kDown, GaitChoice::kTrot);
  REQUIRE(down.plan.status == PlanStatus::kOk);
  INFO((down.validation.violations.empty() ? std::string() : down.validation.violations.front().detail));
  CHECK(down.validation.ok);
  CHECK(down.validation.dynamics.max_line_tilt_rad > 0.0);
  CHECK(down.validation.dynamics.max_line_tilt_rad < PipelineOptions{}.validation.dynamics.max_line_tilt);

  // The same body 2 cm to the left: every diagonal's line has the COM beside it, the body would
  // topple about it, and the phase fails, naming the pair. The four-feet instants stay balanced.
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  const RobotModel robot = BuiltinRobot();
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, PipelineOptions{});
  Plan shifted = down.plan;
  for (BodyState& b : shifted.body) b.y += 0.02;
  TraversalValidator validator(robot, stairs, map);
  const ValidationReport report = validator.Validate(shifted);
  CHECK_FALSE(report.ok);
  const auto tilt = std::find_if(report.violations.begin(), report.violations.end(),
                                 [](const Violation& v) { return v.kind == ViolationKind::kSupportLineTilt; });
  REQUIRE(tilt != report.violations.end());
  CHECK(tilt->value > PipelineOptions{}.validation.dynamics.max_line_tilt);
  CHECK_THAT(tilt->detail, Catch::Contains("LF+RH") || Catch::Contains("RF+LH"));
  CHECK(report.dynamics.max_line_tilt_rad >= tilt->value);
}
