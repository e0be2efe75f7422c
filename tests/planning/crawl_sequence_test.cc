// The crawl's swing orders are defined along the travel: facing backward the front legs trail.
#include <catch2/catch.hpp>

#include <string>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/crawl_planner.h"
#include "leg_names.h"

using namespace stairplan;

namespace {

// Where leg `leg` stands before footstep `i` lifts off (its last touchdown, or its start).
double FootXBefore(const Plan& plan, std::size_t i, const std::string& leg) {
  double x = 0.0;
  for (std::size_t l = 0; l < plan.legs.size(); ++l) {
    if (plan.legs[l] == leg) x = plan.initial_feet_W[l].x();
  }
  for (std::size_t j = 0; j < i; ++j) {
    if (plan.footsteps[j].leg == leg) x = plan.footsteps[j].position_W.x();
  }
  return x;
}

// Whether the leg of footstep i trails (stands behind along the travel) the leg `other`.
bool Trails(const Plan& plan, std::size_t i, const std::string& other) {
  return plan.footsteps[i].from_W.x() < FootXBefore(plan, i, other) - 1e-9;
}

}  // namespace

TEST_CASE("each crawl order swings the legs it names along the travel, facing either way and up or down", "[planning][crawl]") {
  for (const TravelDirection direction : {TravelDirection::kUp, TravelDirection::kDown}) {
    for (const Facing facing : {Facing::kForward, Facing::kBackward}) {
      StairSpec spec;
      spec.direction = direction;
      const Staircase stairs(spec);
      const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, facing);
      for (const CrawlSequence sequence : {CrawlSequence::kLateral, CrawlSequence::kLateralLeadingFirst, CrawlSequence::kPairs}) {
        CrawlSettings settings;
        settings.sequence = sequence;
        const Plan plan = PlanCrawlFootholds(BuiltinRobot(), stairs, map, settings);
        INFO(ToString(direction) << ", facing " << (facing == Facing::kForward ? "forward" : "backward") << ", order "
                                 << static_cast<int>(sequence));
        REQUIRE(plan.status == PlanStatus::kOk);
        REQUIRE(plan.footsteps.size() % 4 == 0);
        for (std::size_t c = 0; c < plan.footsteps.size(); c += 4) {
          INFO("cycle from footstep " << c);
          if (sequence == CrawlSequence::kPairs) {
            // Both trailing legs first: each trails its own side's other leg.
            CHECK(Trails(plan, c, testing::SameSideLeg(plan.footsteps[c].leg)));
            CHECK(Trails(plan, c + 1, testing::SameSideLeg(plan.footsteps[c + 1].leg)));
            CHECK(plan.footsteps[c].leg[0] != plan.footsteps[c + 1].leg[0]);
            continue;
          }
          // One side's two legs, then the other side's, right first.
          for (const std::size_t first : {c, c + 2}) {
            CHECK(plan.footsteps[first].leg[0] == (first == c ? 'R' : 'L'));
            CHECK(plan.footsteps[first + 1].leg == testing::SameSideLeg(plan.footsteps[first].leg));
            CHECK(Trails(plan, first, plan.footsteps[first + 1].leg) == (sequence == CrawlSequence::kLateral));
          }
        }
      }
    }
  }
}

TEST_CASE("crawl orders by name, and each lateral order's other", "[planning][crawl]") {
  CHECK(ParseCrawlSequence("lateral") == CrawlSequence::kLateral);
  CHECK(ParseCrawlSequence("leading-first") == CrawlSequence::kLateralLeadingFirst);
  CHECK(ParseCrawlSequence("pairs") == CrawlSequence::kPairs);
  CHECK_THROWS_WITH(ParseCrawlSequence("trot"), Catch::Contains("leading-first"));
  CHECK(OtherLateralOrder(CrawlSequence::kLateral) == CrawlSequence::kLateralLeadingFirst);
  CHECK(OtherLateralOrder(CrawlSequence::kLateralLeadingFirst) == CrawlSequence::kLateral);
  CHECK(OtherLateralOrder(CrawlSequence::kPairs) == CrawlSequence::kPairs);
}
