// Swings that travel low before they rise (Footstep::swing_approach_share, the 2012 paper's
// swing): their path and their round trip through plan.json (the paper crawl's use of them:
// paper_crawl_test.cc).
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include "stairplan/planning/plan_json.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/planning/swing_trajectory.h"

using namespace stairplan;

TEST_CASE("a swing with an approach share travels low first, then rises, then crosses", "[swing][paper]") {
  const Eigen::Vector3d from(0.0, 0.0, 0.0), to(0.27, 0.0, 0.17);
  const double apex = 0.19;
  const SwingSettings settings;  // rises in the first quarter, lowers in the last
  const SwingTrajectory lift_first(from, to, apex, settings);
  const SwingTrajectory approach(from, to, apex, settings, 0.5);
  const double rise_end = settings.lift_fraction;
  // The first half of the rise moves the foot half way, a tenth of the rise above its foothold.
  CHECK(approach.At(0.5 * rise_end).x() == Approx(0.135));
  CHECK(approach.At(0.5 * rise_end).z() == Approx(0.019));
  // Then it rises straight up to the apex, where the lift-first swing has not moved forward.
  CHECK(approach.At(rise_end).x() == Approx(0.135));
  CHECK(approach.At(rise_end).z() == Approx(apex));
  CHECK(lift_first.At(rise_end).x() == Approx(0.0).margin(1e-12));
  double last_x = from.x();
  for (int i = 0; i <= 200; ++i) {
    const double s = i / 200.0;
    const Eigen::Vector3d p = approach.At(s);
    CHECK(p.x() >= last_x - 1e-12);
    last_x = p.x();
    CHECK(p.z() >= from.z() - 1e-12);
    CHECK(p.z() <= apex + 1e-12);
    // Low (at most a tenth of the rise) until the approach is done.
    if (s <= 0.5 * rise_end) CHECK(p.z() <= from.z() + 0.1 * (apex - from.z()) + 1e-12);
    // The same descent as the lift-first swing.
    if (s >= 1.0 - settings.lower_fraction) CHECK((p - lift_first.At(s)).norm() == Approx(0.0).margin(1e-12));
  }
  CHECK((approach.At(1.0) - to).norm() == Approx(0.0).margin(1e-12));
  CHECK_THROWS_AS(SwingTrajectory(from, to, apex, settings, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(SwingTrajectory(from, to, apex, settings, -0.1), std::invalid_argument);
}

TEST_CASE("plan.json keeps a swing's approach share and refuses one out of range", "[swing][paper]") {
  StairSpec spec;
  spec.steps = 2;
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  Plan plan;
  plan.robot_name = "test";
  plan.legs = {"LF", "RF", "LH", "RH"};
  plan.initial_feet_W.assign(4, Eigen::Vector3d::Zero());
  Footstep step;
  step.leg = "RF";
  step.t_liftoff = 0.1;
  step.t_touchdown = 0.6;
  step.position_W = Eigen::Vector3d(0.3, -0.1, spec.rise);
  step.swing_apex_z = spec.rise + 0.02;
  step.swing_approach_share = 0.4;
  plan.footsteps.push_back(step);
  plan.body.push_back(BodyState{});
  nlohmann::json json = PlanToJson(plan, stairs, map);
  const PlanFile back = ReadPlanJson(json.dump(), "plan.json");
  REQUIRE(back.plan.footsteps.size() == 1);
  CHECK(back.plan.footsteps[0].swing_approach_share == Approx(0.4));
  json["footsteps"][0]["swing_approach_share"] = 1.5;
  try {
    ReadPlanJson(json.dump(), "plan.json");
    FAIL("an approach share of 1.5 was accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("swing_approach_share") != std::string::npos);
    CHECK(std::string(e.what()).find("plan.json") != std::string::npos);
  }
  // A lift-first swing writes no share, so plans without approaches read as before.
  plan.footsteps[0].swing_approach_share = 0.0;
  CHECK_FALSE(PlanToJson(plan, stairs, map)["footsteps"][0].contains("swing_approach_share"));
}
