// The gait enum: names that round-trip through plan.json, which gaits are quasi-static, and the
// step planner's controllers refusing the paper's crawls (they are not controllers).
#include <catch2/catch.hpp>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/plan_gait.h"
#include "stairplan/planning/step/gait_pattern.h"
#include "stairplan/planning/step/step_planner_settings.h"

using namespace stairplan;

TEST_CASE("gaits: each name parses back to its gait, other text to none", "[plan][gait]") {
  for (const Gait g : kAllGaits) {
    CAPTURE(ToString(g));
    REQUIRE(ParseGait(ToString(g)).has_value());
    CHECK(*ParseGait(ToString(g)) == g);
    CHECK(std::string(GaitName(g)) == ToString(g));
  }
  CHECK_FALSE(ParseGait("").has_value());
  CHECK_FALSE(ParseGait("Crawl").has_value());
  CHECK_FALSE(ParseGait("crawl ").has_value());
  CHECK(std::string(GaitName(std::nullopt)).empty());
}

TEST_CASE("gaits: the crawls and the walk are quasi-static, the trot is not", "[plan][gait]") {
  CHECK(IsQuasiStatic(Gait::kCrawl));
  CHECK(IsQuasiStatic(Gait::kCrawlAlternate));
  CHECK(IsQuasiStatic(Gait::kPaperCrawl));
  CHECK(IsQuasiStatic(Gait::kPaperCrawlAlternate));
  CHECK(IsQuasiStatic(Gait::kWalk));
  CHECK_FALSE(IsQuasiStatic(Gait::kTrot));
}

TEST_CASE("gaits: the walk and the trot are judged dynamically, the crawls are not", "[plan][gait]") {
  for (const Gait g : kAllGaits) {
    CAPTURE(ToString(g));
    CHECK(IsJudgedDynamically(g) == (g == Gait::kWalk || g == Gait::kTrot));
  }
}

TEST_CASE("gaits: the paper's crawls have no controller pattern and no controller walks them", "[plan][gait][step]") {
  CHECK(PatternOf(Gait::kCrawl).legs_per_phase == 1);
  CHECK(PatternOf(Gait::kTrot).legs_per_phase == 2);
  CHECK(&PatternOf(Gait::kWalk) == &PatternOf(Gait::kCrawl));  // the walk swings in the crawl's order
  CHECK_THROWS_AS(PatternOf(Gait::kPaperCrawl), std::invalid_argument);
  StepPlannerSettings settings;
  settings.gaits = {Gait::kCrawl, Gait::kPaperCrawlAlternate};
  CHECK_THROWS_WITH(settings.Validate(), Catch::Contains("gaits") && Catch::Contains("paper_crawl_alt"));
}
