// FittedLayouts: the order in which the body search tries the crawl's foothold layouts.
#include <catch2/catch.hpp>

#include <set>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/crawl_planner.h"

using namespace stairplan;

TEST_CASE("the body search tries each stance length's best-fitting offsets first, whole first strides before halved ones",
          "[planning][crawl]") {
  for (const double run : {0.22, 0.27, 0.33}) {
    StairSpec spec;
    spec.run = run;
    const Staircase stairs(spec);
    const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
    const std::vector<CrawlSettings> layouts = FittedLayouts(BuiltinRobot(), stairs, map, CrawlSettings{});
    INFO("run " << run << ": " << layouts.size() << " layouts");
    REQUIRE(layouts.size() >= 6);
    // The first three: the three stance lengths (nearest the hip spacing, one fewer, one more),
    // each at its best-fitting offset, with whole first strides.
    std::set<int> lengths;
    for (std::size_t i = 0; i < 3; ++i) {
      lengths.insert(layouts[i].stance_treads);
      CHECK(layouts[i].trail_first_stride == 1.0);
    }
    CHECK(lengths.size() == 3);
    // Every layout with a halved first stride comes after the same layout with a whole one.
    for (std::size_t i = 0; i < layouts.size(); ++i) {
      if (layouts[i].trail_first_stride == 1.0) continue;
      bool whole_before = false;
      for (std::size_t j = 0; j < i; ++j) {
        whole_before = whole_before || (layouts[j].trail_first_stride == 1.0 && layouts[j].stance_treads == layouts[i].stance_treads &&
                                        layouts[j].lead_offset == layouts[i].lead_offset &&
                                        layouts[j].trail_offset == layouts[i].trail_offset);
      }
      CHECK(whole_before);
    }
  }
}
