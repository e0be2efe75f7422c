// A downstream program: loads a robot, resolves the default stairs, plans a crawl, and checks
// that every footstep landed in a step region. Exit 0 when it did.
#include <iostream>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/crawl_planner.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: stair_summary ROBOT.urdf\n";
    return 2;
  }
  const stairplan::RobotModel robot = stairplan::RobotModel::FromUrdfFile(argv[1]);
  const stairplan::Staircase stairs(stairplan::StairSpec{});
  const auto map = stairplan::ConstrainedMap::FromStaircase(stairs, stairplan::Facing::kForward);
  const stairplan::Plan plan = stairplan::PlanCrawl(robot, stairs, map);
  int inside = 0;
  for (const auto& step : plan.footsteps) inside += step.in_step_region ? 1 : 0;
  std::cout << robot.name() << ": " << plan.footsteps.size() << " footsteps, " << inside
            << " in step regions, status " << stairplan::ToString(plan.status) << "\n";
  return plan.status == stairplan::PlanStatus::kOk && inside == static_cast<int>(plan.footsteps.size()) ? 0 : 1;
}
