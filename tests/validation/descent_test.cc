// Going down: the body optimisation gives the built-in robot plans for the default stairs that the
// validator accepts, facing forward and backward (the shanks stay off the
// nosings behind the feet, every touchdown inside its step region), and a body a robot can follow.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "leg_row_pipeline.h"
#include "sanitized.h"

using namespace stairplan;

namespace {

// The built-in robot down the default stairs; `body`: the body optimisation (the default) or the
// quasi-static path baseline with the pairs crawl it was tuned on.
PipelineResult PlanDescent(Facing facing, bool posture_retries, BodySource body = BodySource::kRecedingHorizonQp) {
  StairSpec spec;
  spec.direction = TravelDirection::kDown;
  spec.steps = testing::FullOrSanitized(spec.steps, 3);  // a shorter flight under the sanitizers
  const Staircase stairs(spec);
  PipelineOptions options = body == BodySource::kQuasiStaticPath ? testing::PathBaselinePipeline() : PipelineOptions{};
  options.facing = facing;
  if (!posture_retries) options.posture_retries.clear();
  return RunPipeline(BuiltinRobot(), stairs, options);
}

std::string FirstViolation(const ValidationReport& r) {
  if (r.violations.empty()) return "none";
  const Violation& v = r.violations.front();
  return "t=" + std::to_string(v.t) + " " + v.leg + " " + ToString(v.kind) + " " + v.detail;
}

}  // namespace

TEST_CASE("the built-in robot's default descents validate, facing forward and backward", "[validator][descent]") {
  for (const Facing facing : {Facing::kForward, Facing::kBackward}) {
    // Under the sanitizers (a minute a 7-step plan) the backward descent alone, the harder of the
    // two, on 3 steps.
    if (testing::kSanitized && facing == Facing::kForward) continue;
    const PipelineResult r = PlanDescent(facing, true);
    INFO((facing == Facing::kForward ? "forward" : "backward") << ": first violation " << FirstViolation(r.validation));
    REQUIRE(r.plan.status == PlanStatus::kOk);
    REQUIRE(r.validated);
    CHECK(r.validation.ok);
    CHECK(r.validation.min_clearance_m > 0.005);
    CHECK(r.validation.min_stability_margin_m > 0.01);
    // It really goes down the flight (1.19 m; 0.51 m under the sanitizers): the body ends more
    // than 85 % of it lower.
    REQUIRE(r.plan.body.size() > 2);
    CHECK(r.plan.body.front().z - r.plan.body.back().z > testing::FullOrSanitized(1.0, 0.43));
    for (const Footstep& f : r.plan.footsteps) CHECK(f.in_step_region);
    // A body a robot can follow: no jumps between samples.
    CHECK(PeakBodyAcceleration(r.plan.body) < 5.5);
    // The map it was planned on is recorded, for validate and simulate to rebuild.
    CHECK(std::isfinite(r.plan.hip_height_fraction));
  }
}

TEST_CASE("without its posture retries the quasi-static path's forward descent is rejected (the default retries none)",
          "[validator][descent]") {
  // A witness of what the retries do, not of new code: the normal build runs it (a minute under
  // the sanitizers, whose pipeline runs are the test above).
  if (testing::kSanitized) return;
  const PipelineResult r = PlanDescent(Facing::kForward, false, BodySource::kQuasiStaticPath);
  REQUIRE(r.validated);
  CHECK_FALSE(r.validation.ok);
}
