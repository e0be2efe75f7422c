#include "planning/crawl_planner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>

#include "geometry/field_error.h"

namespace stairplan {
namespace {

// The paper's crawl: one leg at a time, hind right, hind left, front right, front left.
constexpr std::array<const char*, 4> kCrawlOrder = {"RH", "LH", "RF", "LF"};

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

Interval XRange(const Polygon2& poly) {
  Interval r{poly.vertices.front().x(), poly.vertices.front().x()};
  for (const auto& v : poly.vertices) {
    r.lo = std::min(r.lo, v.x());
    r.hi = std::max(r.hi, v.x());
  }
  return r;
}

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
  const Interval bottom = XRange(map.stair(0).step_region);
  const Interval top = XRange(map.stair(last).step_region);
  std::deque<double> lattice;
  for (int k = 1; k < last; ++k) {
    if (map.stair(k).step_region.empty()) continue;
    const Interval r = XRange(map.stair(k).step_region);
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

struct LegTrack {
  std::string name;
  Eigen::Vector2d foot_offset_W;  // foot relative to the body origin in the world, horizontal
  bool front = false;
  int start_index = 0;
  int swing_slot = 0;             // position in the crawl order
};

Plan Infeasible(Plan plan, const std::string& reason) {
  plan.status = PlanStatus::kInfeasible;
  plan.status_reason = reason;
  return plan;
}

}  // namespace

void CrawlSettings::Validate() const {
  const auto check = [](const char* name, double v, double lo, double hi) {
    if (!std::isfinite(v) || v <= lo || v > hi) {
      throw FieldError(name, "must be in (" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
    }
  };
  check("swing_duration", swing_duration, 0.0, 5.0);
  check("hip_height_fraction", hip_height_fraction, 0.0, 1.0);
  check("sample_period", sample_period, 0.0, 1.0);
  check("start_gap", start_gap, -1.0, 5.0);
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
  double reach = 0.0, hip_z = 0.0, foot_radius = 0.0, front_x = -1e9;
  for (const LegModel& leg : robot.legs()) {
    LegTrack track;
    track.name = leg.name;
    track.foot_offset_W = rotation * Eigen::Vector2d(leg.hip_B.x(), leg.foot_zero_B.y());
    track.front = leg.hip_B.x() > 0.0;
    track.swing_slot = static_cast<int>(std::find(kCrawlOrder.begin(), kCrawlOrder.end(), leg.name) - kCrawlOrder.begin());
    front_x = std::max(front_x, track.foot_offset_W.x());
    reach += leg.max_reach / 4.0;
    hip_z += leg.hip_B.z() / 4.0;
    foot_radius += leg.foot_radius / 4.0;
    tracks.push_back(track);
  }
  // Start with the leading feet just before the flight's first step region.
  const Interval bottom = XRange(map.stair(0).step_region);
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
    const auto it = std::upper_bound(lattice.begin(), lattice.end(), want + 1e-9);
    if (it == lattice.begin()) return Infeasible(plan, "landing_before is too short for the robot's " + track.name + " foot");
    track.start_index = static_cast<int>(it - lattice.begin()) - 1;
    cycles = std::max(cycles, first_top - track.start_index);
  }
  for (const LegTrack& track : tracks) {
    if (track.start_index + cycles >= static_cast<int>(lattice.size())) {
      return Infeasible(plan, "landing_after is too short for the robot's " + track.name + " foot");
    }
  }
  const double hip_height = settings.hip_height_fraction * reach;

  // Foot contact point of leg `l` at lattice index k.
  const auto foothold = [&](const LegTrack& l, int k) {
    const double x = lattice[static_cast<std::size_t>(k)];
    const double y = l.foot_offset_W.y();
    return Eigen::Vector3d(x, y, stairs.HeightAt(x, y));
  };
  for (const LegTrack& l : tracks) plan.initial_feet_W.push_back(foothold(l, l.start_index));

  const double T = settings.swing_duration;
  for (int c = 0; c < cycles; ++c) {
    for (std::size_t slot = 0; slot < kCrawlOrder.size(); ++slot) {
      const auto leg = std::find_if(tracks.begin(), tracks.end(), [&](const LegTrack& l) { return l.name == kCrawlOrder[slot]; });
      Footstep step;
      step.leg = leg->name;
      step.t_liftoff = (4.0 * c + static_cast<double>(slot)) * T;
      step.t_touchdown = step.t_liftoff + T;
      step.from_W = foothold(*leg, leg->start_index + c);
      step.position_W = foothold(*leg, leg->start_index + c + 1);
      step.stair_index = map.StairAt(step.position_W.head<2>());
      step.in_step_region = step.stair_index >= 0 && map.InStepRegion(step.stair_index, step.position_W.head<2>());
      plan.footsteps.push_back(step);
    }
  }

  // The body follows the feet: horizontally the mean of (foot - offset), vertically the mean foot
  // height plus the hip height, pitched along the line from the hind to the front feet.
  const double duration = 4.0 * cycles * T;
  const int samples = static_cast<int>(std::ceil(duration / settings.sample_period - 1e-9));
  for (int s = 0; s <= samples; ++s) {
    const double t = std::min(duration, s * settings.sample_period);
    Eigen::Vector2d sum_xy = Eigen::Vector2d::Zero();
    double sum_z = 0.0, front_xz[2] = {0, 0}, hind_xz[2] = {0, 0};
    for (const LegTrack& l : tracks) {
      const int cycle = std::min(cycles - 1, static_cast<int>(std::floor(t / (4.0 * T))));
      const double phase = (t - cycle * 4.0 * T) / T - l.swing_slot;  // 0..1 during this leg's swing
      const int done = cycle + (phase >= 1.0 ? 1 : 0);
      const double a = (phase > 0.0 && phase < 1.0) ? phase : 0.0;  // swing progress
      const Eigen::Vector3d p0 = foothold(l, l.start_index + done);
      const Eigen::Vector3d p = a > 0.0 ? (1.0 - a) * p0 + a * foothold(l, l.start_index + done + 1) : p0;
      sum_xy += p.head<2>() - l.foot_offset_W;
      sum_z += p.z();
      double* side = l.front ? front_xz : hind_xz;
      side[0] += p.x() / 2.0;
      side[1] += p.z() / 2.0;
    }
    BodyState b;
    b.t = t;
    b.x = sum_xy.x() / 4.0;
    b.y = sum_xy.y() / 4.0;
    b.z = sum_z / 4.0 + foot_radius + hip_height - hip_z;
    b.yaw = yaw;
    b.pitch = -std::atan2(front_xz[1] - hind_xz[1], (front_xz[0] - hind_xz[0]) * std::cos(yaw));
    plan.body.push_back(b);
  }
  return plan;
}

}  // namespace stairplan
