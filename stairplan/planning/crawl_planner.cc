#include "stairplan/planning/crawl_planner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {
namespace {

// The legs one cycle swings, in order. The sequences are defined along the travel: facing
// backward the front legs trail.
std::array<const char*, 4> SwingOrder(CrawlSequence sequence, Facing facing) {
  struct Slot {
    bool right;
    bool trailing;
  };
  std::array<Slot, 4> slots = {{{true, true}, {false, true}, {true, false}, {false, false}}};  // kPairs
  if (sequence == CrawlSequence::kLateral) slots = {{{true, true}, {true, false}, {false, true}, {false, false}}};
  if (sequence == CrawlSequence::kLateralLeadingFirst) slots = {{{true, false}, {true, true}, {false, false}, {false, true}}};
  std::array<const char*, 4> order{};
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const bool hind = slots[i].trailing == (facing == Facing::kForward);
    order[i] = slots[i].right ? (hind ? "RH" : "RF") : (hind ? "LH" : "LF");
  }
  return order;
}

// Swing slots per cycle: four one leg at a time, two when the diagonal pairs swing together.
int SlotsPerCycle(const CrawlSettings& settings) { return settings.diagonal_pairs ? 2 : 4; }

// The slot in its cycle of the swing `order` puts at `slot`: that slot, one leg at a time; trotting,
// the first slot for the legs of order[0]'s diagonal (RH and LF, or RF and LH) and the second for
// the other diagonal.
double SlotOf(const CrawlSettings& settings, const std::array<const char*, 4>& order, std::size_t slot) {
  if (!settings.diagonal_pairs) return static_cast<double>(slot);
  const auto on_rh_lf = [](const char* leg) {
    const std::string name(leg);
    return name == "RH" || name == "LF";
  };
  return on_rh_lf(order[slot]) == on_rh_lf(order[0]) ? 0.0 : 1.0;
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
  const Eigen::Vector3d* given_start = nullptr;  // CrawlSettings::start_feet's, when given
};

Plan Infeasible(Plan plan, const std::string& reason) {
  plan.status = PlanStatus::kInfeasible;
  plan.status_reason = reason;
  return plan;
}

}  // namespace

CrawlSequence ParseCrawlSequence(const std::string& text) {
  if (text == "pairs") return CrawlSequence::kPairs;
  if (text == "lateral") return CrawlSequence::kLateral;
  if (text == "leading-first") return CrawlSequence::kLateralLeadingFirst;
  throw std::invalid_argument("crawl-sequence: must be 'pairs', 'lateral' or 'leading-first' (got '" + text + "')");
}

CrawlSequence OtherLateralOrder(CrawlSequence sequence) {
  if (sequence == CrawlSequence::kLateral) return CrawlSequence::kLateralLeadingFirst;
  if (sequence == CrawlSequence::kLateralLeadingFirst) return CrawlSequence::kLateral;
  return sequence;
}

void CrawlSettings::Validate() const {
  RequireInRange("swing_duration", swing_duration, 0.05, 5.0);
  RequireInRange("shift_duration", shift_duration, 0.0, 5.0);
  RequireInRange("start_gap", start_gap, -1.0, 5.0);
  RequireInRange("trailing_margin", trailing_margin, 0.0, 0.2);
  RequireInRange("stance_treads", stance_treads, 0, 10);
  RequireInRange("fit_footholds", fit_footholds, 0, 100);
  RequireInRange("lead_first_stride", lead_first_stride, 0.1, 1.0);
  RequireInRange("trail_first_stride", trail_first_stride, 0.1, 1.0);
  RequireInRange("lead_offset", lead_offset, -0.5, 0.5);
  RequireInRange("trail_offset", trail_offset, -0.5, 0.5);
  RequireInRange("refit_body_acceleration", refit_body_acceleration, 0.0, 1e4);
  RequireInRange("min_support_inradius", min_support_inradius, 0.0, 0.2);
  body.Validate();
  swing.Validate();
}

namespace {

// The crawl's footsteps on the footholds `settings` lay out, with no body.
Plan CrawlFootsteps(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                    const CrawlSettings& settings) {
  Plan plan;
  plan.robot_name = robot.name();
  plan.robot_source = robot.source();
  plan.facing = map.facing();
  plan.cadence_s = settings.swing_duration;
  plan.gait = Gait::kCrawl;
  for (const LegModel& leg : robot.legs()) plan.legs.push_back(leg.name);

  const std::vector<double> lattice = FootholdLattice(stairs, map);
  if (lattice.size() < 2) return Infeasible(plan, "the landings have no step region");
  const double yaw = map.facing() == Facing::kForward ? 0.0 : M_PI;
  const Eigen::Rotation2Dd rotation(yaw);

  const std::vector<Eigen::Vector3d>& given = settings.start_feet;
  if (!given.empty() && given.size() != robot.legs().size()) {
    throw std::invalid_argument("CrawlSettings::start_feet: one per leg of the robot (" + std::to_string(robot.legs().size()) + ")");
  }
  std::vector<LegTrack> tracks;
  double front_x = -1e9;
  for (const LegModel& leg : robot.legs()) {
    LegTrack track;
    track.name = leg.name;
    if (!given.empty()) track.given_start = &given[tracks.size()];
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
    const double want = track.given_start ? track.given_start->x() : body_x0 + track.foot_offset_W.x();
    // The nearest foothold, so feet start as close under their hips as the lattice allows.
    const auto it = std::upper_bound(lattice.begin(), lattice.end(), want);
    if (it == lattice.begin()) return Infeasible(plan, "landing_before is too short for the robot's " + track.name + " foot");
    const bool next_is_nearer = it != lattice.end() && *it - want < want - *(it - 1) && map.StairAt({*it, 0.0}) == 0;
    track.start_index = static_cast<int>(it - lattice.begin()) - (next_is_nearer ? 0 : 1);
  }
  if (settings.stance_treads > 0) {
    int lead = 0;
    for (const LegTrack& l : tracks) {
      if (l.foot_offset_W.x() >= front_x - 1e-9) lead = std::max(lead, l.start_index);
    }
    for (LegTrack& l : tracks) {
      if (l.foot_offset_W.x() < front_x - 1e-9) l.start_index = lead - settings.stance_treads;
      if (l.start_index < 0) return Infeasible(plan, "landing_before is too short for the robot's " + l.name + " foot");
    }
  }
  for (const LegTrack& track : tracks) cycles = std::max(cycles, first_top - track.start_index);
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
    const bool leading = l.foot_offset_W.x() >= lead_x - 1e-9;
    const double offset = leading ? settings.lead_offset : settings.trail_offset;
    if (offset != 0.0) x = ClampToStepRegion(map, x, x + offset, settings.trailing_margin);
    if (settings.keep_stance_length && l.foot_offset_W.x() < lead_x - 1e-9) {
      const int lead_k = std::min(k + lead_start - l.start_index, static_cast<int>(lattice.size()) - 1);
      const double stance = (lead_x - l.foot_offset_W.x()) * std::cos(pitch);
      x = ClampToStepRegion(map, x, lattice[static_cast<std::size_t>(lead_k)] - stance, settings.trailing_margin);
    }
    const double y = l.foot_offset_W.y();
    return Eigen::Vector3d(x, y, stairs.HeightAt(x, y));
  };
  // Where a leg starts: its first foothold, or that far toward its second (a shorter first stride).
  const auto start = [&](const LegTrack& l) {
    if (l.given_start) return *l.given_start;
    const Eigen::Vector3d a = foothold(l, l.start_index);
    const bool leading = l.foot_offset_W.x() >= lead_x - 1e-9;
    const double f = leading ? settings.lead_first_stride : settings.trail_first_stride;
    if (f >= 1.0) return a;
    const Eigen::Vector3d b = foothold(l, l.start_index + 1);
    const double x = b.x() + f * (a.x() - b.x());
    return Eigen::Vector3d(x, a.y(), stairs.HeightAt(x, a.y()));
  };
  for (const LegTrack& l : tracks) plan.initial_feet_W.push_back(start(l));
  // A given start must leave each foot a stride forward, not back or beyond its reach (a layout
  // with more or fewer treads between the feet than the start has).
  for (const LegTrack& l : tracks) {
    if (!l.given_start || l.start_index + 1 >= static_cast<int>(lattice.size())) continue;
    const double stride = foothold(l, l.start_index + 1).x() - start(l).x();
    if (!(stride > 0.0 && stride < 2.0 * MeanRun(stairs.spec()))) {
      return Infeasible(plan, "the " + l.name + " foot's first stride from its start (" + std::to_string(stride) + " m) is not forward within two runs");
    }
  }

  // Each swing is preceded by a four-feet phase in which the COM moves over the next triangle.
  const double slot_duration = settings.shift_duration + settings.swing_duration;
  const std::array<const char*, 4> order = SwingOrder(settings.sequence, map.facing());
  for (int c = 0; c < cycles; ++c) {
    for (std::size_t slot = 0; slot < order.size(); ++slot) {
      const auto leg = std::find_if(tracks.begin(), tracks.end(), [&](const LegTrack& l) { return l.name == order[slot]; });
      Footstep step;
      step.leg = leg->name;
      step.t_liftoff = (SlotsPerCycle(settings) * c + SlotOf(settings, order, slot)) * slot_duration + settings.shift_duration;
      step.t_touchdown = step.t_liftoff + settings.swing_duration;
      step.from_W = c == 0 ? start(*leg) : foothold(*leg, leg->start_index + c);
      step.position_W = foothold(*leg, leg->start_index + c + 1);
      step.stair_index = map.StairAt(step.position_W.head<2>());
      step.in_step_region = step.stair_index >= 0 && map.InStepRegion(step.stair_index, step.position_W.head<2>());
      step.swing_apex_z = SwingTrajectory(step.from_W, step.position_W, stairs, settings.swing).apex_z();
      plan.footsteps.push_back(step);
    }
  }
  std::stable_sort(plan.footsteps.begin(), plan.footsteps.end(),
                   [](const Footstep& a, const Footstep& b) { return a.t_touchdown < b.t_touchdown; });
  return plan;
}

// The crawl with the footholds `settings` lay out and the quasi-static path over them, fitted to
// the stairs' stances when `fit_stairs` is given (unfitted otherwise, for screening layouts).
Plan PlanCrawlLayout(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                     const CrawlSettings& settings, const Staircase* fit_stairs) {
  Plan plan = CrawlFootsteps(robot, stairs, map, settings);
  if (plan.status != PlanStatus::kOk) return plan;
  BodyPathSettings body = settings.body;
  body.swing = settings.swing;
  const double yaw = map.facing() == Facing::kForward ? 0.0 : M_PI;
  plan.body = BodyPathForFootsteps(robot, plan.legs, plan.initial_feet_W, plan.footsteps, yaw, body, fit_stairs);
  return plan;
}

// A foothold layout the crawl can try instead of the one it was given (see CrawlSettings).
struct FootholdLayout {
  int stance_treads = 0;
  double lead_offset = 0.0;
  double trail_offset = 0.0;
  double trail_first_stride = 1.0;
  int fit = 0;  // the offset's rank among its stance length's: 0 fits the hip spacing best

  CrawlSettings Apply(CrawlSettings settings) const {
    settings.stance_treads = stance_treads;
    settings.lead_offset = lead_offset;
    settings.trail_offset = trail_offset;
    settings.trail_first_stride = trail_first_stride;
    return settings;
  }
};

// Layouts whose stance lengths fit the robot. Through a crawl cycle the trailing feet are s and
// s - 1 treads behind the leading ones, plus the offset d between the two pairs' footholds in
// their step regions. Stretched legs run out of reach (and into their knee limits) long before
// squeezed ones do, so the longer stance, s run + d, is fitted to the hip spacing along the
// pitched body: for the s nearest that and its neighbours, d as near it as the narrowest step
// region allows, the largest d the regions allow the other way, and none; each also with the
// trailing legs' first stride halved (their first touchdown is the farthest reach of all: the
// body is still over the hindmost triangle).
std::vector<FootholdLayout> CandidateLayouts(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                                             const CrawlSettings& settings) {
  double front = -1e9, hind = 1e9;
  for (const LegModel& leg : robot.legs()) {
    front = std::max(front, leg.hip_B.x());
    hind = std::min(hind, leg.hip_B.x());
  }
  const double pitch = settings.body.pitch_fraction * std::atan(std::abs(FlightSlope(stairs)));
  const double spacing = (front - hind) * std::cos(pitch);
  const double run = MeanRun(stairs.spec());
  // Each pair moves at most this far from its region's centre, so d spans twice that.
  double half = 1e9;
  for (int k = 1; k + 1 < map.size(); ++k) {
    if (map.stair(k).step_region.empty()) continue;
    const Extent r = map.stair(k).step_region.XExtent();
    half = std::min(half, 0.5 * (r.hi - r.lo) - settings.trailing_margin);
  }
  const double d_max = half < 1e8 ? 2.0 * std::max(0.0, half) : 0.0;
  const int nearest = std::max(1, static_cast<int>(std::lround(spacing / run)));
  std::vector<FootholdLayout> layouts;
  for (const int s : {nearest, nearest - 1, nearest + 1}) {
    if (s < 1) continue;
    const double want = spacing - s * run;
    std::vector<double> ds = {std::clamp(want, -d_max, d_max)};
    if (std::abs(ds.front() + std::copysign(d_max, want)) > 1e-3) ds.push_back(-std::copysign(d_max, want));
    if (std::abs(ds.front()) > 1e-3) ds.push_back(0.0);
    for (std::size_t fit = 0; fit < ds.size(); ++fit) {
      for (const double first : {1.0, 0.5}) layouts.push_back({s, 0.5 * ds[fit], -0.5 * ds[fit], first, static_cast<int>(fit)});
    }
  }
  return layouts;
}

// The radius of the largest circle inside the triangle a, b, c seen from above (0 when they
// are in line): how far inside its support the centre of mass can stand.
double Inradius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector2d ab = (b - a).head<2>(), ac = (c - a).head<2>();
  const double area = 0.5 * std::abs(ab.x() * ac.y() - ab.y() * ac.x());
  const double perimeter = ab.norm() + ac.norm() + (c - b).head<2>().norm();
  return perimeter > 0.0 ? 2.0 * area / perimeter : 0.0;
}

// Calls visit(step, swinging, feet) for the plan's footsteps in order: `feet` where the plan's
// feet stand just before that touchdown (in plan.legs order), `swinging` the stepping leg's index
// there. Steps of a leg the plan does not name are skipped; visit returns false to stop.
template <typename Visit>
void ReplayTouchdowns(const Plan& plan, Visit visit) {
  std::vector<Eigen::Vector3d> feet = plan.initial_feet_W;
  if (feet.size() != plan.legs.size()) return;
  for (const Footstep& step : plan.footsteps) {
    const auto leg = std::find(plan.legs.begin(), plan.legs.end(), step.leg);
    if (leg == plan.legs.end()) continue;
    const auto swinging = static_cast<std::size_t>(leg - plan.legs.begin());
    if (!visit(step, swinging, feet)) return;
    feet[swinging] = step.position_W;
  }
}

// Touchdown stances of crawl plans through the stance check, and the support of every swing.
class TouchdownChecker {
 public:
  TouchdownChecker(const RobotModel& robot, const Staircase& stairs, const CrawlSettings& settings)
      : checker_(robot, stairs), body_(settings.body), min_inradius_(settings.min_support_inradius) {}

  int Crowded(const Plan& plan) const { return CrowdedTouchdowns(checker_.kinematics().robot(), plan).touchdowns; }

  // Touchdowns whose stance, with the plan's own body pose, fails the stance check, swings whose
  // support triangle is too thin to stand over, plus one when the body jumps (accelerates faster
  // than `max_acceleration` between samples; 0: not checked).
  int Failed(const Plan& plan, double max_acceleration) {
    const int all = static_cast<int>(plan.footsteps.size());
    const int failed = Count(plan, all, [this](const BodyPose& pose, const Contacts& feet) { return checker_.Check(pose, feet).ok(); });
    return failed + ThinSupports(plan) +
           (max_acceleration > 0.0 && PeakBodyAcceleration(plan.body) > max_acceleration ? 1 : 0);
  }

  // Swings whose three stance feet hold no circle of min_support_inradius: no body motion keeps
  // the centre of mass over them with a margin.
  int ThinSupports(const Plan& plan) const {
    int thin = 0;
    ReplayTouchdowns(plan, [&](const Footstep&, std::size_t swinging, const std::vector<Eigen::Vector3d>& feet) {
      std::array<Eigen::Vector3d, 3> stance;
      std::size_t n = 0;
      for (std::size_t i = 0; i < feet.size() && n < stance.size(); ++i) {
        if (i != swinging) stance[n++] = feet[i];
      }
      if (n == stance.size() && Inradius(stance[0], stance[1], stance[2]) < min_inradius_) ++thin;
      return true;
    });
    return thin;
  }

  // Touchdowns at which no body pose passes among the plan's own shifted along x by up to the
  // posture fit's max_shift, at any height from 0.2 m below to 0.1 m above it: footholds that no
  // posture fit can stand on, and swings too thin to stand over. Cheap enough to screen layouts
  // on sketches (no posture fit). Counts up to `limit` (a layout that bad is of no interest).
  int Unstandable(const Plan& plan, int limit) {
    const int thin = ThinSupports(plan);
    if (thin >= limit) return thin;
    return thin + Count(plan, limit - thin, [this](const BodyPose& pose, const Contacts& feet) {
      const int shifts = static_cast<int>(std::floor(body_.max_shift / body_.shift_step + 1e-9));
      for (int k = 0; k <= 2 * shifts; ++k) {
        BodyPose shifted = pose;
        shifted.position_W.x() += (k % 2 == 0 ? -1.0 : 1.0) * ((k + 1) / 2) * body_.shift_step;
        const double z = pose.position_W.z();
        if (!checker_.FeasibleBodyHeights(shifted, feet, z - 0.2, z + 0.1, 0.02, 0.02).empty()) return true;
      }
      return false;
    });
  }

 private:
  using Contacts = std::array<Eigen::Vector3d, 4>;

  template <typename Passes>
  int Count(const Plan& plan, int limit, Passes passes) {
    int failed = 0;
    ReplayTouchdowns(plan, [&](const Footstep& step, std::size_t swinging, const std::vector<Eigen::Vector3d>& feet) {
      Contacts contacts;  // the feet just after the touchdown, in the kinematics' leg order
      for (std::size_t i = 0; i < feet.size() && i < contacts.size(); ++i) {
        contacts[static_cast<std::size_t>(checker_.kinematics().LegIndex(plan.legs[i]))] = i == swinging ? step.position_W : feet[i];
      }
      return passes(BodyPoseAt(plan.body, step.t_touchdown), contacts) || ++failed < limit;
    });
    return failed;
  }

  StanceChecker checker_;
  BodyPathSettings body_;
  double min_inradius_ = 0.0;
};

}  // namespace

TouchdownCrowding CrowdedTouchdowns(const RobotModel& robot, const Plan& plan) {
  TouchdownCrowding crowding;
  ReplayTouchdowns(plan, [&](const Footstep& step, std::size_t swinging, const std::vector<Eigen::Vector3d>& feet) {
    for (std::size_t i = 0; i < feet.size(); ++i) {
      const double apart = robot.leg(plan.legs[i]).foot_radius + robot.leg(step.leg).foot_radius;
      if (i != swinging && (feet[i] - step.position_W).head<2>().norm() < apart) {
        if (crowding.touchdowns++ == 0) {
          crowding.first_t = step.t_touchdown;
          crowding.leg = step.leg;
          crowding.onto = plan.legs[i];
        }
        break;
      }
    }
    return true;
  });
  return crowding;
}

std::vector<CrawlSettings> FittedLayouts(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                                         const CrawlSettings& settings) {
  // Each stance length's best-fitting offset before any other offset, and whole first strides
  // before halved ones: a layout that fails on its stance length usually fails with the first
  // stride halved too, and the next stance length's best fit is the likelier rescue.
  std::vector<FootholdLayout> layouts = CandidateLayouts(robot, stairs, map, settings);
  std::stable_sort(layouts.begin(), layouts.end(), [](const FootholdLayout& a, const FootholdLayout& b) {
    return std::make_pair(a.fit, a.trail_first_stride < 1.0) < std::make_pair(b.fit, b.trail_first_stride < 1.0);
  });
  std::vector<CrawlSettings> fitted;
  for (const FootholdLayout& layout : layouts) {
    fitted.push_back(layout.Apply(settings));
    fitted.back().fit_footholds = 0;
  }
  return fitted;
}

Plan PlanCrawlFootholds(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                        const CrawlSettings& settings) {
  settings.Validate();
  return CrawlFootsteps(robot, stairs, map, settings);
}

Plan PlanCrawl(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const CrawlSettings& settings) {
  settings.Validate();
  Plan best = PlanCrawlLayout(robot, stairs, map, settings, &stairs);
  if (settings.fit_footholds <= 0 || best.status != PlanStatus::kOk) return best;
  TouchdownChecker checker(robot, stairs, settings);
  const double jump = settings.refit_body_acceleration;
  int failed = checker.Failed(best, jump);
  if (failed == 0) return best;
  // Feet landing on one another are no plan at all: a first layout with such touchdowns gives way
  // to the least unstandable layout whose feet keep apart, even one failing other touchdowns.
  const bool crowded = checker.Crowded(best) > 0;
  std::optional<std::pair<int, CrawlSettings>> apart;
  // Other layouts, in CandidateLayouts' order: each is sketched (no posture fit) and screened, and
  // one whose every touchdown some posture can stand on is planned in full at once; when none
  // screens clean, the least unstandable ones are, up to fit_footholds full plans in all. Only a
  // layout with every touchdown passing replaces the first: one that merely fails fewer is not
  // worth leaving the lattice the other planners are tuned on (stairbot's QP body on its forward
  // descent is infeasible on the footholds that fail 14 touchdowns of the first layout's 15).
  std::vector<std::pair<int, CrawlSettings>> screened;
  int full = 0, least = failed;  // full plans made; fewest unstandable touchdowns screened
  const auto passes_in_full = [&](const CrawlSettings& layout) {
    ++full;
    Plan plan = PlanCrawlLayout(robot, stairs, map, layout, &stairs);
    if (checker.Failed(plan, jump) > 0) return false;
    best = std::move(plan);
    return true;
  };
  for (const FootholdLayout& layout : CandidateLayouts(robot, stairs, map, settings)) {
    const CrawlSettings candidate = layout.Apply(settings);
    const Plan sketch = PlanCrawlLayout(robot, stairs, map, candidate, nullptr);
    if (sketch.status != PlanStatus::kOk) continue;
    const int unstandable = checker.Unstandable(sketch, crowded ? failed : least);
    least = std::min(least, unstandable);
    if (crowded && checker.Crowded(sketch) == 0 && (!apart || unstandable < apart->first)) apart.emplace(unstandable, candidate);
    if (unstandable == 0 && passes_in_full(candidate)) return best;
    if (full >= settings.fit_footholds) break;
    if (unstandable > 0 && unstandable < failed) screened.emplace_back(unstandable, candidate);
  }
  std::stable_sort(screened.begin(), screened.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < screened.size() && full < settings.fit_footholds; ++i) {
    if (passes_in_full(screened[i].second)) return best;
  }
  if (crowded && apart) return PlanCrawlLayout(robot, stairs, map, apart->second, &stairs);
  return best;
}

}  // namespace stairplan
