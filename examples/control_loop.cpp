// A 333 Hz control loop (the 3 ms re-selection period of seed 000 [0033]) over the default stairs:
// the body planner's Update() every cycle, the state advanced along the plan, and the latency
// percentiles at the end. The first traversal fills the planner's caches of kinematic and
// collision bounds; the second one is timed as a robot would run it.
//
//   ./control_loop [up|down] [forward|backward]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/crawl_planner.h"

using namespace stairplan;

namespace {

constexpr double kPeriod = 0.003;  // [s]

struct Pass {
  std::vector<double> latency_us;
  int stale = 0, infeasible = 0;
  double max_shift = 0.0, min_pitch = 0.0, max_pitch = 0.0;
};

Pass Traverse(BodyPlanner& planner) {
  Pass pass;
  planner.Reset();
  BodyState state = planner.StartState();
  const double end = planner.schedule().end_time();
  for (double now = 0.0; now <= end; now += kPeriod) {
    const auto t0 = std::chrono::steady_clock::now();
    const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    if (out.solves == 1) pass.latency_us.push_back(us);  // the warm-up cycle is not a control cycle
    pass.stale += out.status == BodyPlanStatus::kStale ? 1 : 0;
    pass.infeasible += out.status == BodyPlanStatus::kInfeasible ? 1 : 0;
    pass.max_shift = std::max(pass.max_shift, out.knots[0].com_shift);
    pass.min_pitch = std::min(pass.min_pitch, out.knots[0].pitch);
    pass.max_pitch = std::max(pass.max_pitch, out.knots[0].pitch);
    state = planner.Interpolate(now + kPeriod);  // the robot tracks the plan perfectly
  }
  return pass;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  StairSpec spec;
  Facing facing = Facing::kForward;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "down") == 0) spec.direction = TravelDirection::kDown;
    if (std::strcmp(argv[i], "backward") == 0) facing = Facing::kBackward;
  }
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, facing);
  const RobotModel& robot = BuiltinRobot();
  const Plan footsteps = PlanCrawlFootholds(robot, stairs, map);
  if (footsteps.status != PlanStatus::kOk) {
    std::printf("crawl plan infeasible: %s\n", footsteps.status_reason.c_str());
    return 3;
  }
  BodyPlanner planner(robot, stairs, map, footsteps);
  const auto t0 = std::chrono::steady_clock::now();
  Traverse(planner);  // fills the bound caches
  const double fill_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Pass pass = Traverse(planner);
  std::printf("control loop: %s, %s %s, %zu cycles at %.0f Hz over %.2f s\n", robot.name().c_str(),
              ToString(stairs.direction()), ToString(facing), pass.latency_us.size() + 1, 1.0 / kPeriod,
              planner.schedule().end_time());
  std::printf("  first traversal (fills the caches): %.2f s\n", fill_s);
  std::printf("  Update latency [us]: p50 %.1f  p90 %.1f  p99 %.1f  max %.1f\n", Percentile(pass.latency_us, 0.5),
              Percentile(pass.latency_us, 0.9), Percentile(pass.latency_us, 0.99), Percentile(pass.latency_us, 1.0));
  std::printf("  stale cycles: %d, infeasible cycles: %d\n", pass.stale, pass.infeasible);
  std::printf("  com_shift max %.3f m, pitch in [%.3f, %.3f] rad\n", pass.max_shift, pass.min_pitch, pass.max_pitch);
  return pass.infeasible == 0 ? 0 : 3;
}
