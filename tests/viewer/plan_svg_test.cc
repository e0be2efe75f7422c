// plan.svg: the title says INVALID with the first violation when validation failed, each violation
// is ringed in the side and the top view, and the top view shows the feet apart across the stairs.
#include <catch2/catch.hpp>

#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/planning/plan_svg.h"
#include "test_paths.h"

namespace {

std::size_t PlanSvgCount(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("plan.svg: INVALID and the first violation in the title, violations ringed in both views", "[viewer][svg]") {
  const stairplan::PlanFile file = stairplan::ReadPlanJsonFile(stairplan::testing::SourceDir() +
                                                               "/tests/fuzz/corpus/plan_json/short_plan.json");
  const stairplan::Staircase stairs(file.stairs);
  const stairplan::ConstrainedMap map = stairplan::ConstrainedMap::FromStaircase(stairs, file.facing);
  const stairplan::Footstep& step = file.plan.footsteps.front();

  stairplan::ValidationReport report;
  report.ok = false;
  report.violations.push_back({step.t_touchdown, step.leg, stairplan::ViolationKind::kFootOutsideStepRegion, 0.04, "stair 0"});
  const std::string invalid = stairplan::PlanToSvg(file.plan, stairs, map, &report);
  CHECK(invalid.find("INVALID: foot_outside_step_region (" + step.leg + ")") != std::string::npos);
  CHECK(PlanSvgCount(invalid, "r='9' fill='none' stroke='#ff00cc'") == 2);  // side and top view
  CHECK(invalid.find("top view") != std::string::npos);
  // Every footstep is drawn twice: on its tread in the side view, at its x-y in the top view.
  CHECK(PlanSvgCount(invalid, "<title>") == 2 * file.plan.footsteps.size());

  stairplan::ValidationReport valid;
  valid.min_clearance_m = 0.012;
  const std::string ok = stairplan::PlanToSvg(file.plan, stairs, map, &valid);
  CHECK(ok.find("INVALID") == std::string::npos);
  CHECK(ok.find(": valid, min clearance 12 mm") != std::string::npos);
  CHECK(PlanSvgCount(ok, "stroke='#ff00cc'") == 0);
}
