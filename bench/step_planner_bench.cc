// Per-cycle latency of the step planner: one re-selection among the default 15 controllers
// (5 cadences x 3 gaits) with 8 footsteps each, over inputs recorded along a traversal of the
// default stairs. Reports p50 and p99 per Update; the goal is p99 <= 20 us. The same with the
// IK reach model the pipeline plans with (every footstep's reach by KDL IK within the joint
// limits, not the geometric band). Also times a whole offline traversal.
#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/ik_reach_model.h"
#include "stairplan/planning/step/step_planner.h"
#include "stairplan/planning/step/step_planner_driver.h"

namespace {

using namespace stairplan;

// Inputs seen by the planner while it walks the flight, committing its own first footstep.
std::vector<StepPlannerInput> RecordInputs(StepPlanner& planner, const ConstrainedMap& map) {
  std::vector<StepPlannerInput> inputs;
  StepPlannerInput in;
  in.velocity_W = {0.15, 0.0};
  in.body_xy_W = {-0.8, 0.0};
  for (int l = 0; l < 4; ++l) {
    const Eigen::Vector2d p = planner.SnapIntoRegion(0, planner.NeutralFootXY(l, in.body_xy_W));
    in.legs[static_cast<std::size_t>(l)].foot_W = {p.x(), p.y(), map.stair(0).z};
    in.legs[static_cast<std::size_t>(l)].stair = 0;
  }
  for (int cycle = 0; cycle < 60; ++cycle) {
    inputs.push_back(in);
    const int chosen = planner.Update(in);
    if (chosen < 0) break;
    const ControllerEvaluation& e = planner.evaluation(chosen);
    for (int k = 0; k < e.step_count && e.steps[static_cast<std::size_t>(k)].t_liftoff <= in.now_s; ++k) {
      const PlannedStep& s = e.steps[static_cast<std::size_t>(k)];
      auto& leg = in.legs[static_cast<std::size_t>(s.leg)];
      leg.foot_W = s.target_W;
      leg.stair = s.target_stair;
      leg.last_touchdown_s = s.t_touchdown;
    }
    const double T = planner.controllers()[static_cast<std::size_t>(chosen)].cadence_s;
    in.now_s += T;
    in.body_xy_W.x() += in.velocity_W.x() * T;
  }
  planner.Reset();
  return inputs;
}

// Re-selections over the recorded inputs, p50/p99/max per Update in the counters. `ik`: with the
// IK reach model instead of the geometric band.
void RunUpdates(benchmark::State& state, bool ik) {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const RobotModel& robot = BuiltinRobot();
  StepPlanner planner(robot, map, StepPlannerSettings{}, ik ? std::make_shared<IkReachModel>(robot) : nullptr);
  const std::vector<StepPlannerInput> inputs = RecordInputs(planner, map);
  std::vector<double> us;
  us.reserve(1 << 20);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(planner.Update(inputs[i]));
    const auto t1 = std::chrono::steady_clock::now();
    if (us.size() < us.capacity()) us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    i = (i + 1) % inputs.size();
  }
  std::sort(us.begin(), us.end());
  const auto at = [&](double q) { return us.empty() ? 0.0 : us[static_cast<std::size_t>(q * static_cast<double>(us.size() - 1))]; };
  state.counters["p50_us"] = at(0.50);
  state.counters["p99_us"] = at(0.99);
  state.counters["max_us"] = at(1.0);
  state.counters["controllers"] = static_cast<double>(planner.controllers().size());
  state.counters["footsteps"] = planner.settings().horizon_steps;
}

void BM_StepPlannerUpdate(benchmark::State& state) { RunUpdates(state, false); }
BENCHMARK(BM_StepPlannerUpdate)->Unit(benchmark::kMicrosecond);

void BM_StepPlannerUpdateIkReach(benchmark::State& state) { RunUpdates(state, true); }
BENCHMARK(BM_StepPlannerUpdateIkReach)->Unit(benchmark::kMicrosecond);

// For scale: a whole offline traversal of the default stairs (construction, every re-selection,
// body samples), what `stairplan plan` pays for its footsteps.
void BM_PlanWithStepPlanner(benchmark::State& state) {
  const Staircase stairs{StairSpec{}};
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  for (auto _ : state) benchmark::DoNotOptimize(PlanWithStepPlanner(BuiltinRobot(), stairs, map).footsteps.size());
}
BENCHMARK(BM_PlanWithStepPlanner)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
