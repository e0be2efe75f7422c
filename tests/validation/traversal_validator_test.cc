// The validator passes good plans and catches planted faults with the right kind.
#include <catch2/catch.hpp>

#include <iostream>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/planning/validation/traversal_validator.h"

using namespace stairplan;

namespace {

struct Scenario {
  Staircase stairs;
  PipelineResult result;
  Scenario(TravelDirection direction, Facing facing) : stairs(Spec(direction)) {
    PipelineOptions options;
    options.facing = facing;
    result = RunPipeline(BuiltinRobot(), stairs, options);
  }
  static StairSpec Spec(TravelDirection direction) {
    StairSpec spec;
    spec.direction = direction;
    return spec;
  }
  ValidationReport Validate(const Plan& plan) {
    TraversalValidator validator(BuiltinRobot(), stairs, result.map);
    return validator.Validate(plan);
  }
};

std::string Describe(const ValidationReport& r) {
  std::string text = "min clearance " + std::to_string(r.min_clearance_m) + ", min margin " +
                     std::to_string(r.min_stability_margin_m) + ", violations:";
  for (const Violation& v : r.violations) {
    text += "\n  t=" + std::to_string(v.t) + " " + v.leg + " " + ToString(v.kind) + " " + std::to_string(v.value) + " " + v.detail;
  }
  return text;
}

bool HasKind(const ValidationReport& r, ViolationKind kind, const std::string& leg_prefix = "") {
  for (const Violation& v : r.violations) {
    if (v.kind == kind && v.leg.rfind(leg_prefix, 0) == 0) return true;
  }
  return false;
}

// The default climb, planned once for all the cases below: they are sections of one test, so one
// process plans it (seconds in the normal build, a quarter of a minute under the sanitizers).
Scenario& DefaultClimb() {
  static Scenario scenario(TravelDirection::kUp, Facing::kForward);
  return scenario;
}

}  // namespace

TEST_CASE("the validator passes the default plan and catches planted faults in it", "[validator]") {
  Scenario& s = DefaultClimb();
  SECTION("the validator passes the default plan") {
    REQUIRE(s.result.plan.status == PlanStatus::kOk);
    const ValidationReport r = s.Validate(s.result.plan);
    INFO(Describe(r));
    CHECK(r.ok);
    CHECK(r.violations.empty());
    CHECK(r.min_clearance_m > 0.005);
    CHECK(r.min_stability_margin_m > 0.01);
    CHECK(r.samples > 1000);
  }

  SECTION("a foot moved off its step region is caught") {
    Plan plan = s.result.plan;
    Footstep& step = plan.footsteps.at(13);  // a foot landing on a tread mid-flight
    const StairSurface& tread = s.stairs.surface(step.stair_index);
    step.position_W.x() = tread.x_end - 0.01;  // under the nosing above: a collision region
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    CHECK_FALSE(r.ok);
    CHECK(HasKind(r, ViolationKind::kFootOutsideStepRegion, step.leg));
  }

  SECTION("a body lowered into the stairs is caught") {
    Plan plan = s.result.plan;
    for (BodyState& b : plan.body) {
      if (b.t > 8.0 && b.t < 9.0) b.z -= 0.40;
    }
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    CHECK_FALSE(r.ok);
    CHECK(HasKind(r, ViolationKind::kBodyCollision, "body"));
    // When: the collision inside the lowered stretch (the drop into it is also a body_acceleration,
    // reported at the sample before it).
    for (const Violation& v : r.violations) {
      if (v.kind != ViolationKind::kBodyCollision) continue;
      CHECK(v.t > 8.0);
      CHECK(v.t < 9.0);
    }
  }

  SECTION("a breach that deepens over a stretch is listed at its first instant with its worst value") {
    // The body sinks into the stairs deeper and deeper over a second: the first instant that
    // breaks the clearance is the shallowest; a user judging the plan needs the depth too.
    Plan plan = s.result.plan;
    for (BodyState& b : plan.body) {
      if (b.t > 8.0 && b.t < 9.0) b.z -= 0.3 + 0.2 * (b.t - 8.0);
    }
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    int listed = 0;
    for (const Violation& v : r.violations) {
      if (v.kind != ViolationKind::kBodyCollision) continue;
      ++listed;
      CHECK(v.worst < v.value - 0.05);  // 20 cm deeper by the end, on whichever stair part
      CHECK(v.t_worst > v.t);
      CHECK(v.t_worst < 9.0);
      CHECK(v.worst >= r.min_clearance_m);
    }
    CHECK(listed == 1);
    for (const Violation& v : r.violations) {
      const bool worst_or_equal = LargerIsWorse(v.kind) ? v.worst >= v.value : v.worst <= v.value;
      CHECK(worst_or_equal);
    }
  }

  SECTION("a body that jumps between its samples is caught, though every instant of it is fine") {
    CHECK_FALSE(HasKind(s.result.validation, ViolationKind::kBodyAcceleration, "body"));
    Plan plan = s.result.plan;
    // 2 cm up from one sample on: a step the interpolated instants pass, 8 m/s^2 at 20 Hz samples,
    // too little to flag; 8 cm (32 m/s^2) is a jump.
    const auto raise = [&](double dz) {
      Plan p = plan;
      for (BodyState& b : p.body) {
        if (b.t > 8.02) b.z += dz;
      }
      return s.Validate(p);
    };
    const ValidationReport small = raise(0.02);
    INFO(Describe(small));
    CHECK_FALSE(HasKind(small, ViolationKind::kBodyAcceleration, "body"));
    const ValidationReport jump = raise(0.08);
    INFO(Describe(jump));
    CHECK_FALSE(jump.ok);
    REQUIRE(HasKind(jump, ViolationKind::kBodyAcceleration, "body"));
    for (const Violation& v : jump.violations) {
      if (v.kind != ViolationKind::kBodyAcceleration) continue;
      CHECK(v.t == Approx(8.0).margin(0.06));
      CHECK(v.value > 19.62);
      CHECK(v.detail == "along z");
    }
  }

  SECTION("the crawls, the paper's among them, are judged quasi-static; a trot or no gait is not") {
    // 25 cm sideways from t = 8 s on: the COM leaves the support triangles, and the body jumps.
    Plan plan = s.result.plan;
    for (BodyState& b : plan.body) {
      if (b.t > 8.02) b.y += 0.25;
    }
    const auto judged_quasi_static = [&](std::optional<Gait> gait) {
      plan.gait = gait;
      const ValidationReport r = s.Validate(plan);
      INFO(GaitName(gait) << ": " << Describe(r));
      const bool stability = HasKind(r, ViolationKind::kStability, "body");
      CHECK(stability == HasKind(r, ViolationKind::kBodyAcceleration, "body"));
      return stability;
    };
    for (const Gait g : {Gait::kCrawl, Gait::kCrawlAlternate, Gait::kPaperCrawl, Gait::kPaperCrawlAlternate}) {
      CHECK(judged_quasi_static(g));
    }
    CHECK_FALSE(judged_quasi_static(Gait::kTrot));
    CHECK_FALSE(judged_quasi_static(std::nullopt));
  }

  SECTION("a hind knee driven into a riser is caught") {
    // The hind knees point back; pitching the body nose-up lowers the hips behind and drives the
    // hind shanks' tops (the knees) into the nosing of the riser below them.
    Plan plan = s.result.plan;
    for (BodyState& b : plan.body) {
      if (b.t > 8.0 && b.t < 10.0) b.pitch -= 0.35;
    }
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    CHECK_FALSE(r.ok);
    bool hind_link_hit = false;
    for (const Violation& v : r.violations) {
      const bool hind = v.leg == "LH" || v.leg == "RH";
      const bool leg_link = v.detail.find("shank") != std::string::npos || v.detail.find("thigh") != std::string::npos;
      if (v.kind == ViolationKind::kStairCollision && hind && leg_link) hind_link_hit = true;
    }
    CHECK(hind_link_hit);
  }

  SECTION("a hind foot landing where its front foot stands is caught as a leg collision") {
    // On a tread shorter than the body a crawl's hind foot can be sent to the foothold its front
    // foot has not lifted from yet: a foothold inside the step region, which only the same side's
    // pair of legs shows to be taken.
    Plan plan = s.result.plan;
    Footstep* hind = nullptr;
    for (Footstep& f : plan.footsteps) {
      if (f.leg == "RH" && f.t_touchdown > 6.0) {
        hind = &f;
        break;
      }
    }
    REQUIRE(hind != nullptr);
    const Footstep* front = nullptr;  // RF's foothold when RH lands
    for (const Footstep& f : plan.footsteps) {
      if (f.leg == "RF" && f.t_touchdown < hind->t_touchdown) front = &f;
    }
    REQUIRE(front != nullptr);
    hind->position_W = front->position_W;
    hind->stair_index = front->stair_index;
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    CHECK_FALSE(r.ok);
    bool same_side = false;
    for (const Violation& v : r.violations) {
      if (v.kind == ViolationKind::kLegCollision && v.leg == "RF/RH") same_side = v.value < 0.0;
    }
    CHECK(same_side);
  }

  SECTION("a swing too low to clear a nosing is caught") {
    Plan plan = s.result.plan;
    Footstep& step = plan.footsteps.at(12);
    REQUIRE(step.position_W.z() > step.from_W.z());  // a step up onto the next tread
    step.swing_apex_z = step.from_W.z() + 0.03;      // never rises to the tread it climbs to
    const ValidationReport r = s.Validate(plan);
    INFO(Describe(r));
    CHECK_FALSE(r.ok);
    CHECK(HasKind(r, ViolationKind::kStairCollision, step.leg));
  }
}
