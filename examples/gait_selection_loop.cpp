// The step planner's controller re-selected every 3 ms (seed 000 [0033]) against a moving robot:
// the body tracks the commanded speed with a wobble of a centimetre, and every cycle the
// controllers (cadences x gaits) are scored for the next phase from the body predicted at its
// start, with the IK reach model the pipeline plans with. The selection in force when a phase
// begins is committed: its legs swing to their targets. At the end, the re-selection latency
// percentiles, how often the selection changed within a phase, and what was committed.
//
//   ./gait_selection_loop [up|down]
//
// Exit code 0 when the feet reach the last surface, every footstep inside its step region;
// 3 otherwise.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/builtin_robot.h"
#include "stairplan/planning/step/ik_reach_model.h"
#include "stairplan/planning/step/step_planner.h"

using namespace stairplan;

namespace {

constexpr double kPeriod = 0.003;    // [s]
constexpr double kMaxTime = 120.0;   // [s] of robot time
constexpr double kWobbleX = 0.01;    // [m], the body's tracking error along the travel
constexpr double kWobbleY = 0.005;   // [m], sideways

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

// Where the feet start: under the hips, the leading ones start_gap before the end of the first
// step region (as the step planner's offline driver starts).
Eigen::Vector2d StartBody(const StepPlanner& planner, const ConstrainedMap& map, const StepPlannerSettings& settings) {
  double region_hi = -std::numeric_limits<double>::infinity();
  for (const auto& v : map.stair(0).step_region.vertices) region_hi = std::max(region_hi, v.x());
  double lead = -std::numeric_limits<double>::infinity();
  for (int l = 0; l < 4; ++l) lead = std::max(lead, planner.NeutralFootXY(l, Eigen::Vector2d::Zero()).x());
  return {region_hi - settings.start_gap - lead, 0.0};
}

}  // namespace

int main(int argc, char** argv) {
  StairSpec spec;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "down") == 0) spec.direction = TravelDirection::kDown;
  }
  const Staircase stairs(spec);
  const ConstrainedMap map = ConstrainedMap::FromStaircase(stairs, Facing::kForward);
  const RobotModel& robot = BuiltinRobot();
  const StepPlannerSettings settings;
  StepPlanner planner(robot, map, settings, std::make_shared<IkReachModel>(robot));
  const auto& controllers = planner.controllers();

  const Eigen::Vector2d body0 = StartBody(planner, map, settings);
  const Eigen::Vector2d velocity(settings.speed, 0.0);
  StepPlannerInput input;
  input.velocity_W = velocity;
  for (int l = 0; l < 4; ++l) {
    const Eigen::Vector2d xy = planner.SnapIntoRegion(0, planner.NeutralFootXY(l, body0));
    input.legs[static_cast<std::size_t>(l)] = {Eigen::Vector3d(xy.x(), xy.y(), map.stair(0).z), 0, 0.0};
  }

  std::vector<double> latency_us;
  latency_us.reserve(static_cast<std::size_t>(kMaxTime / kPeriod) + 1);
  std::vector<int> committed(controllers.size(), 0);
  int changes = 0, phases = 0, outside = 0, footsteps = 0;
  bool arrived = false, stuck = false;
  double next_phase = settings.settle_s;  // the first swing waits for the body to move off the diagonal
  int selected = -1;
  const int last = map.size() - 1;
  double t = 0.0;
  for (; t < kMaxTime && !arrived && !stuck; t += kPeriod) {
    // The robot as measured now, and where it will be when the next phase begins.
    const Eigen::Vector2d wobble(kWobbleX * std::sin(2.0 * M_PI * 1.3 * t), kWobbleY * std::sin(2.0 * M_PI * 0.7 * t));
    const Eigen::Vector2d measured = body0 + velocity * t + wobble;
    input.now_s = next_phase;
    input.body_xy_W = measured + velocity * (next_phase - t);
    const auto t0 = std::chrono::steady_clock::now();
    const int chosen = planner.Update(input);
    latency_us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    if (selected >= 0 && chosen != selected) ++changes;
    selected = chosen;
    if (t + kPeriod <= next_phase) continue;
    // The phase begins before the next cycle: the selection in force is committed.
    if (chosen < 0) {
      stuck = true;
      break;
    }
    const ControllerEvaluation& e = planner.evaluation(chosen);
    for (int k = 0; k < e.step_count; ++k) {
      const PlannedStep& s = e.steps[static_cast<std::size_t>(k)];
      if (s.t_liftoff > next_phase + 1e-9) break;
      StepLegState& leg = input.legs[static_cast<std::size_t>(s.leg)];
      leg.foot_W = s.target_W;
      leg.stair = s.target_stair;
      leg.last_touchdown_s = s.t_touchdown;
      outside += map.InStepRegion(s.target_stair, s.target_W.head<2>()) ? 0 : 1;
      ++footsteps;
    }
    ++committed[static_cast<std::size_t>(chosen)];
    ++phases;
    next_phase += controllers[static_cast<std::size_t>(chosen)].cadence_s;
    selected = -1;  // a new phase: its first selection is not a change of mind
    arrived = std::all_of(input.legs.begin(), input.legs.end(), [&](const StepLegState& l) { return l.stair == last; });
  }

  std::printf("gait selection loop: %s, %s, %zu re-selections at %.0f Hz over %.2f s, %d phases (%d footsteps)\n",
              robot.name().c_str(), ToString(stairs.direction()), latency_us.size(), 1.0 / kPeriod, t, phases, footsteps);
  std::printf("  re-selection [us]: p50 %.1f  p99 %.1f  max %.1f (%zu controllers, IK reach model)\n",
              Percentile(latency_us, 0.5), Percentile(latency_us, 0.99), Percentile(latency_us, 1.0), controllers.size());
  std::printf("  the selection changed %d times within a phase\n", changes);
  std::printf("  committed:");
  for (std::size_t i = 0; i < controllers.size(); ++i) {
    if (committed[i] > 0) std::printf(" %s %.2f s x %d;", ToString(controllers[i].gait), controllers[i].cadence_s, committed[i]);
  }
  std::printf("\n  arrived: %s; footsteps outside their step regions: %d%s\n", arrived ? "yes" : "no", outside,
              stuck ? "; stopped: no admissible controller when a phase began" : "");
  return arrived && outside == 0 && !stuck ? 0 : 3;
}
