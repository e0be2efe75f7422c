// The crawl's foothold layouts on a tread shorter than the body: Unitree A1 (hips 0.366 m apart)
// down stairs of 0.28 m runs. On the step-region lattice its hind feet stand one tread behind the
// front ones, and the crawl moves the hind legs first: each hind foot is sent to the foothold its
// front foot has not lifted from yet. The layout search must leave that layout for one whose feet
// keep apart, though no layout passes every touchdown there.
#include <catch2/catch.hpp>

#include <map>
#include <optional>
#include <string>

#include "planning/crawl_planner.h"
#include "planning/plan_pipeline.h"
#include "test_paths.h"

using namespace stairplan;

namespace {

// Touchdowns within the two feet's radii (seen from above) of a foot standing there.
int CrowdedTouchdowns(const RobotModel& robot, const Plan& plan) {
  std::map<std::string, Eigen::Vector3d> feet;
  for (std::size_t i = 0; i < plan.legs.size(); ++i) feet[plan.legs[i]] = plan.initial_feet_W.at(i);
  int crowded = 0;
  for (const Footstep& step : plan.footsteps) {
    for (const auto& [leg, foot] : feet) {
      const double apart = robot.leg(leg).foot_radius + robot.leg(step.leg).foot_radius;
      if (leg != step.leg && (foot - step.position_W).head<2>().norm() < apart) ++crowded;
    }
    feet[step.leg] = step.position_W;
  }
  return crowded;
}

}  // namespace

TEST_CASE("a crawl never lands a foot where another stands: Unitree A1 down 0.28 m runs", "[planning][crawl]") {
  const std::string urdf = testing::SharedPath("data/robots/unitree_a1.urdf");
  if (urdf.empty()) {
    WARN("Unitree A1 skipped: ../shared not found");
    return;
  }
  const RobotModel robot = RobotModel::FromUrdfFile(urdf);
  StairSpec spec;
  spec.rise = 0.10;
  spec.run = 0.28;
  spec.direction = TravelDirection::kDown;
  const Staircase stairs(spec);
  const PipelineOptions options;
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, options);
  CrawlSettings lattice = options.crawl;
  lattice.fit_footholds = 0;  // the step-region lattice as laid, no search
  const Plan laid = PlanCrawl(robot, stairs, map, lattice);
  REQUIRE(laid.status == PlanStatus::kOk);
  CHECK(CrowdedTouchdowns(robot, laid) > 0);
  const Plan searched = PlanCrawl(robot, stairs, map, options.crawl);
  REQUIRE(searched.status == PlanStatus::kOk);
  CHECK(CrowdedTouchdowns(robot, searched) == 0);
  for (const Footstep& step : searched.footsteps) CHECK(step.in_step_region);
}
