#include "planning/crawl_planner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>

#include "geometry/field_error.h"
#include "planning/swing_trajectory.h"

namespace stairplan {
namespace {

// The paper's crawl: one leg at a time, hind right, hind left, front right, front left.
constexpr std::array<const char*, 4> kCrawlOrder = {"RH", "LH", "RF", "LF"};

double MeanRun(const StairSpec& spec) {
  if (spec.runs.empty()) return spec.run;
  double sum = 0.0;
  for (double r : spec.runs) sum += r;
  return sum / static_cast<double>(spec.runs.size());
}

// Foothold x positions along the flight: the centre of every tread's step region, extended over
// both landings at the flight's mean run so that the crawl keeps one rhythm throughout.
std::vector<double> FootholdLattice(const Staircase& stairs, const ConstrainedMap& map) {
  const int last = map.size() - 1;
  if (map.stair(0).step_region.empty() || map.stair(last).step_region.empty()) return {};
  const Extent bottom = map.stair(0).step_region.XExtent();
  const Extent top = map.stair(last).step_region.XExtent();
  std::deque<double> lattice;
  for (int k = 1; k < last; ++k) {
    if (map.stair(k).step_region.empty()) continue;
    const Extent r = map.stair(k).step_region.XExtent();
    lattice.push_back(0.5 * (r.lo + r.hi));
  }
  if (lattice.empty()) lattice = {bottom.hi, top.lo};
  const double stride = MeanRun(stairs.spec());
  for (double x = std::min(lattice.front() - stride, bottom.hi); x >= bottom.lo; x = std::min(x, bottom.hi) - stride) {
    lattice.push_front(std::min(x, bottom.hi));
  }
  for (double x = std::max(lattice.back() + stride, top.lo); x <= top.hi; x = std::max(x, top.lo) + stride) {
    lattice.push_back(std::max(x, top.lo));
  }
  return {lattice.begin(), lattice.end()};
}

// Rise over run of the whole flight (positive uphill in travel direction).
double FlightSlope(const Staircase& stairs) {
  const auto& surfaces = stairs.surfaces();
  const double length = surfaces.back().x_begin - surfaces.front().x_end;
  return length > 0.0 ? (surfaces.back().z - surfaces.front().z) / length : 0.0;
}

// `want` moved into the step region of the stair under `centre` (its x extent shrunk by
// `margin`); the centre itself when that region is too narrow.
double ClampToStepRegion(const ConstrainedMap& map, double centre, double want, double margin) {
  const int stair = map.StairAt({centre, 0.0});
  if (stair < 0 || map.stair(stair).step_region.empty()) return centre;
  const Extent r = map.stair(stair).step_region.XExtent();
  if (r.hi - r.lo <= 2.0 * margin) return centre;
  return std::clamp(want, r.lo + margin, r.hi - margin);
}

struct LegTrack {
  std::string name;
  Eigen::Vector2d foot_offset_W;  // foot relative to the body origin in the world, horizontal
  int start_index = 0;
};

Plan Infeasible(Plan plan, const std::string& reason) {
  plan.status = PlanStatus::kInfeasible;
  plan.status_reason = reason;
  return plan;
}

}  // namespace

void CrawlSettings::Validate() const {
  RequireInRange("swing_duration", swing_duration, 0.05, 5.0);
  RequireInRange("shift_duration", shift_duration, 0.0, 5.0);
  RequireInRange("start_gap", start_gap, -1.0, 5.0);
  RequireInRange("trailing_margin", trailing_margin, 0.0, 0.2);
  body.Validate();
  swing.Validate();
}

Plan PlanCrawl(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const CrawlSettings& settings) {
  settings.Validate();
  Plan plan;
  plan.robot_name = robot.name();
  plan.robot_source = robot.source();
  plan.facing = map.facing();
  plan.cadence_s = settings.swing_duration;
  plan.gait = "crawl";
  for (const LegModel& leg : robot.legs()) plan.legs.push_back(leg.name);

  const std::vector<double> lattice = FootholdLattice(stairs, map);
  if (lattice.size() < 2) return Infeasible(plan, "the landings have no step region");
  const double yaw = map.facing() == Facing::kForward ? 0.0 : M_PI;
  const Eigen::Rotation2Dd rotation(yaw);

  std::vector<LegTrack> tracks;
  double front_x = -1e9;
  for (const LegModel& leg : robot.legs()) {
    LegTrack track;
    track.name = leg.name;
    track.foot_offset_W = rotation * Eigen::Vector2d(leg.hip_B.x(), leg.foot_zero_B.y());
    front_x = std::max(front_x, track.foot_offset_W.x());
    tracks.push_back(track);
  }
  // Start with the leading feet just before the flight's first step region.
  const Extent bottom = map.stair(0).step_region.XExtent();
  const double body_x0 = bottom.hi - settings.start_gap - front_x;
  const int last_stair = map.size() - 1;
  int first_top = static_cast<int>(lattice.size());
  for (int i = 0; i < static_cast<int>(lattice.size()); ++i) {
    if (map.StairAt({lattice[static_cast<std::size_t>(i)], 0.0}) == last_stair) {
      first_top = i;
      break;
    }
  }
  int cycles = 0;
  for (LegTrack& track : tracks) {
    const double want = body_x0 + track.foot_offset_W.x();
    // The nearest foothold, so feet start as close under their hips as the lattice allows.
    const auto it = std::upper_bound(lattice.begin(), lattice.end(), want);
    if (it == lattice.begin()) return Infeasible(plan, "landing_before is too short for the robot's " + track.name + " foot");
    const bool next_is_nearer = it != lattice.end() && *it - want < want - *(it - 1) && map.StairAt({*it, 0.0}) == 0;
    track.start_index = static_cast<int>(it - lattice.begin()) - (next_is_nearer ? 0 : 1);
    cycles = std::max(cycles, first_top - track.start_index);
  }
  for (const LegTrack& track : tracks) {
    if (track.start_index + cycles >= static_cast<int>(lattice.size())) {
      return Infeasible(plan, "landing_after is too short for the robot's " + track.name + " foot");
    }
  }
  const double lead_x = front_x;
  const int lead_start = [&] {
    int start = 0;
    for (const LegTrack& l : tracks) {
      if (l.foot_offset_W.x() >= lead_x - 1e-9) start = std::max(start, l.start_index);
    }
    return start;
  }();
  const double pitch = settings.body.pitch_fraction * std::atan(std::abs(FlightSlope(stairs)));
  // Foot contact point of leg `l` at lattice index k. The leading legs stand at step-region centres;
  // the trailing legs as near to one stance length behind them as their own tread's step region
  // allows, so the legs keep the posture the body path assumes whatever the run.
  const auto foothold = [&](const LegTrack& l, int k) {
    double x = lattice[static_cast<std::size_t>(k)];
    if (settings.keep_stance_length && l.foot_offset_W.x() < lead_x - 1e-9) {
      const int lead_k = std::min(k + lead_start - l.start_index, static_cast<int>(lattice.size()) - 1);
      const double stance = (lead_x - l.foot_offset_W.x()) * std::cos(pitch);
      x = ClampToStepRegion(map, x, lattice[static_cast<std::size_t>(lead_k)] - stance, settings.trailing_margin);
    }
    const double y = l.foot_offset_W.y();
    return Eigen::Vector3d(x, y, stairs.HeightAt(x, y));
  };
  for (const LegTrack& l : tracks) plan.initial_feet_W.push_back(foothold(l, l.start_index));

  // Each swing is preceded by a four-feet phase in which the COM moves over the next triangle.
  const double slot_duration = settings.shift_duration + settings.swing_duration;
  for (int c = 0; c < cycles; ++c) {
    for (std::size_t slot = 0; slot < kCrawlOrder.size(); ++slot) {
      const auto leg = std::find_if(tracks.begin(), tracks.end(), [&](const LegTrack& l) { return l.name == kCrawlOrder[slot]; });
      Footstep step;
      step.leg = leg->name;
      step.t_liftoff = (4.0 * c + static_cast<double>(slot)) * slot_duration + settings.shift_duration;
      step.t_touchdown = step.t_liftoff + settings.swing_duration;
      step.from_W = foothold(*leg, leg->start_index + c);
      step.position_W = foothold(*leg, leg->start_index + c + 1);
      step.stair_index = map.StairAt(step.position_W.head<2>());
      step.in_step_region = step.stair_index >= 0 && map.InStepRegion(step.stair_index, step.position_W.head<2>());
      step.swing_apex_z = SwingTrajectory(step.from_W, step.position_W, stairs, settings.swing).apex_z();
      plan.footsteps.push_back(step);
    }
  }
  BodyPathSettings body = settings.body;
  body.swing = settings.swing;
  plan.body = BodyPathForFootsteps(robot, plan.legs, plan.initial_feet_W, plan.footsteps, yaw, body, &stairs);
  return plan;
}

}  // namespace stairplan
