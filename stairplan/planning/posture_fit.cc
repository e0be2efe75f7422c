#include "stairplan/planning/posture_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/shapes.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {
namespace {

// A posture correction from `t` on: a shift along the flight and a height change. A repair (a
// height put back inside its window between two swings) changes the height only.
struct PostureKey {
  double t = 0.0;
  double dx = 0.0;
  double dz = 0.0;
  bool repair = false;
};

// What the fit needs to know about one instant: the feet (swing feet on their swings), the
// support polygon of the stance feet, the uncorrected body pose and the COM target.
struct Instant {
  std::array<Eigen::Vector3d, 4> contacts;
  Polygon2 support;
  BodyPose pose;
  Eigen::Vector2d com = Eigen::Vector2d::Zero();
};

// A stretch of time fitted with one correction: a swing (swings that overlap, merged) or one instant.
struct Segment {
  double t0 = 0.0;
  double t1 = 0.0;
};

class PostureFitter {
 public:
  PostureFitter(const RobotModel& robot, const Staircase& stairs, const std::vector<std::string>& legs,
                const std::vector<Eigen::Vector3d>& initial, const std::vector<Footstep>& footsteps,
                const std::function<Eigen::Vector2d(double)>& com_target, const BodyPathSettings& settings,
                const std::vector<BodyState>& body)
      : checker_(robot, stairs, CheckSettings(settings)), stairs_(stairs), legs_(legs), initial_(initial),
        footsteps_(footsteps), com_target_(com_target), settings_(settings), body_(body) {}

  // The corrections for the instants of `segment`, appended to `keys`, trying `prefer_dx` first
  // so the body keeps its shift when it can: one height, or one eased (SmoothStep) from the
  // segment's start to its end; when none suits every instant at any shift, a chain of eases
  // through some of its instants (FitChain). False when nothing suits them all.
  bool Fit(const Segment& segment, double prefer_dx, std::vector<PostureKey>& keys) {
    const std::vector<double> times = KeyTimes(segment);
    std::vector<Instant> instants;
    std::vector<double> phase;  // eased progress through the segment at each instant
    for (double t : times) {
      instants.push_back(InstantAt(t));
      phase.push_back(segment.t1 > segment.t0 ? SmoothStep((t - segment.t0) / (segment.t1 - segment.t0)) : 0.0);
    }
    std::vector<std::pair<double, std::vector<Interval1>>> standable;  // shifts with a window at every instant
    double best = -1.0;
    PostureKey key, end;
    for (const double dx : Candidates(prefer_dx)) {
      std::vector<Interval1> windows;
      if (!Windows(instants, dx, windows)) continue;
      double dz0 = 0.0, dz1 = 0.0;
      const double slack = FitHeights(windows, phase, dz0, dz1);
      standable.emplace_back(dx, std::move(windows));
      if (slack <= best) continue;
      best = slack;
      key = {segment.t0, dx, dz0};
      end = {segment.t1, dx, dz1};
      if (2.0 * best >= settings_.wide_height_range) break;
    }
    if (best >= 0.0) {
      keys.push_back(key);
      if (segment.t1 > segment.t0) keys.push_back(end);
      return true;
    }
    std::vector<PostureKey> chain, best_chain;
    for (const auto& [dx, windows] : standable) {
      const double slack = FitChain(times, windows, dx, chain);
      if (slack <= best) continue;
      best = slack;
      best_chain = chain;
    }
    keys.insert(keys.end(), best_chain.begin(), best_chain.end());
    return best >= 0.0;
  }

  // The correction at instant t when `eased` (what the keys give there) leaves the heights that
  // pass there by less than height_margin: the nearest height kept clear of the window's ends.
  // False when `eased` is fine, or nothing at its shift passes.
  bool Repair(double t, const PostureKey& eased, PostureKey& repaired) {
    std::vector<Interval1> windows;
    if (!Windows({InstantAt(t)}, eased.dx, windows)) return false;
    const Interval1& w = windows.front();
    if (eased.dz >= w.lo + settings_.height_margin && eased.dz <= w.hi - settings_.height_margin) return false;
    const double keep = Keep(w.hi - w.lo);
    repaired = {t, eased.dx, std::clamp(eased.dz, w.lo + keep, w.hi - keep), true};
    return true;
  }

  // The instants checked in a segment: its ends, every height_key_period between them and, when
  // asked, the corners of the swings inside it (SwingCorners).
  std::vector<double> KeyTimes(const Segment& segment) const {
    std::vector<double> times = {segment.t0};
    const double period = settings_.height_key_period;
    for (double t = segment.t0 + period; t < segment.t1 - 0.25 * period; t += period) times.push_back(t);
    if (segment.t1 > segment.t0) times.push_back(segment.t1);
    if (!settings_.check_swing_corners) return times;
    for (const Footstep& f : footsteps_) {
      for (const double t : SwingCorners(f)) {
        if (t > segment.t0 && t < segment.t1) times.push_back(t);
      }
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end(), [](double a, double b) { return b - a < 1e-6; }), times.end());
    return times;
  }

 private:
  // Where a swing's foot turns (SwingTrajectory): done rising, still above its liftoff, and
  // about to lower, above its touchdown. The rise's end folds the leg most: on the steepest steps
  // the hip's abduction reaches its limit there, and a 0.25 s swing checked every 0.1 s misses it.
  std::array<double, 2> SwingCorners(const Footstep& f) const {
    const double duration = f.t_touchdown - f.t_liftoff;
    return {f.t_liftoff + settings_.swing.lift_fraction * duration, f.t_touchdown - settings_.swing.lower_fraction * duration};
  }

  static StanceSettings CheckSettings(const BodyPathSettings& settings) {
    StanceSettings s;
    s.min_clearance = settings.touchdown_clearance;
    return s;
  }

  Instant InstantAt(double t) const {
    Instant instant;
    std::vector<bool> stance;
    const std::vector<Eigen::Vector3d> feet = FeetAlongSwings(legs_, initial_, footsteps_, t, stairs_, settings_.swing, &stance);
    std::vector<Eigen::Vector2d> support;
    for (std::size_t i = 0; i < legs_.size() && i < 4; ++i) {
      instant.contacts[static_cast<std::size_t>(checker_.kinematics().LegIndex(legs_[i]))] = feet[i];
      if (stance[i]) support.push_back(feet[i].head<2>());
    }
    instant.support = ConvexHull(support);
    instant.pose = BodyPoseAt(body_, t);
    instant.com = com_target_(t);
    return instant;
  }

  // The shifts to try: the preferred one, then 0, +step, -step, +2 step, ... up to max_shift.
  std::vector<double> Candidates(double prefer_dx) const {
    std::vector<double> dxs = {prefer_dx};
    const int shifts = static_cast<int>(std::floor(settings_.max_shift / settings_.shift_step + 1e-9));
    for (int k = 0; k <= 2 * shifts; ++k) {
      const double dx = (k % 2 == 0 ? -1.0 : 1.0) * ((k + 1) / 2) * settings_.shift_step;
      if (std::abs(dx - prefer_dx) > 1e-9) dxs.push_back(dx);
    }
    return dxs;
  }

  // The height corrections that pass at each instant with the body shifted by dx. False as soon
  // as one instant has none, or a shift takes the COM target within shift_margin of the support's edge.
  bool Windows(const std::vector<Instant>& instants, double dx, std::vector<Interval1>& windows) {
    for (const Instant& instant : instants) {
      if (dx != 0.0 && -instant.support.SignedDistance(instant.com + Eigen::Vector2d(dx, 0.0)) < settings_.shift_margin) {
        return false;
      }
      BodyPose pose = instant.pose;
      pose.position_W.x() += dx;
      const double z = pose.position_W.z();
      const Interval1 window = checker_.FeasibleBodyHeights(pose, instant.contacts, z - 0.2, z + 0.1, 0.02, 0.004);
      if (window.empty()) return false;
      windows.push_back({window.lo - z, window.hi - z});
    }
    return true;
  }

  // Heights dz0 -> dz1 (eased by `phase`) inside every window; the largest slack any pair on a grid
  // over the first and last windows reaches, s*, is returned. Of the pairs with slack at least
  // min(s*, max(height_margin, 2 height_centering s*)) (for one window: height_centering of its
  // width from either end), the one that moves the body least is taken.
  double FitHeights(const std::vector<Interval1>& windows, const std::vector<double>& phase, double& dz0,
                    double& dz1) const {
    const std::vector<double> starts = Grid(windows.front()), ends = Grid(windows.back());
    const auto slack = [&](double a, double b) {
      double least = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < windows.size(); ++k) {
        const double z = a + phase[k] * (b - a);
        least = std::min({least, z - windows[k].lo, windows[k].hi - z});
      }
      return least;
    };
    double most = -std::numeric_limits<double>::infinity();
    for (double a : starts) {
      for (double b : ends) most = std::max(most, slack(a, b));
    }
    const double wanted = Keep(2.0 * most);
    double least_motion = std::numeric_limits<double>::infinity();
    for (double a : starts) {
      for (double b : ends) {
        const double motion = std::abs(a) + std::abs(b) + std::abs(b - a);
        if (slack(a, b) < wanted - 1e-12 || motion >= least_motion) continue;
        least_motion = motion;
        dz0 = a;
        dz1 = b;
      }
    }
    return most;
  }

  // Heights for the instants `times` (windows `windows` at shift dx) as a chain of eases between
  // knots, a knot being one of the instants with the body at rest in z there (as at every key):
  // every instant inside its window, and no ease of dz over T faster than
  // max_height_acceleration at its peak (6 dz / T^2), so the body need not jump where the
  // feasible heights move during a swing. Knots take heights on each window's grid; the chain
  // with the largest least slack s* is found first, then among those with slack at least
  // Keep(2 s*) the one that moves the body least, as FitHeights does for one ease. Returns s*
  // (negative: no chain) and the knots' keys in `chain`.
  double FitChain(const std::vector<double>& times, const std::vector<Interval1>& windows, double dx,
                  std::vector<PostureKey>& chain) const {
    const std::size_t n = times.size();
    std::vector<std::vector<double>> heights(n);
    for (std::size_t k = 0; k < n; ++k) heights[k] = Grid(windows[k]);
    const double none = -std::numeric_limits<double>::infinity();
    // The least slack of the ease from (k, a) to (m, b) over the instants k..m (none: too fast).
    const auto ease_slack = [&](std::size_t k, double a, std::size_t m, double b) {
      const double span = times[m] - times[k];
      if (6.0 * std::abs(b - a) > settings_.max_height_acceleration * span * span) return none;
      double least = std::numeric_limits<double>::infinity();
      for (std::size_t i = k; i <= m; ++i) {
        const double z = a + SmoothStep((times[i] - times[k]) / span) * (b - a);
        least = std::min({least, z - windows[i].lo, windows[i].hi - z});
      }
      return least;
    };
    // Pass 1: the best least slack of a chain ending at each knot.
    std::vector<std::vector<double>> slack(n);
    for (std::size_t m = 0; m < n; ++m) {
      for (const double b : heights[m]) {
        double most = m == 0 ? std::min(b - windows[0].lo, windows[0].hi - b) : none;
        for (std::size_t k = 0; k < m; ++k) {
          for (std::size_t g = 0; g < heights[k].size(); ++g) {
            if (slack[k][g] <= most) continue;
            most = std::max(most, std::min(slack[k][g], ease_slack(k, heights[k][g], m, b)));
          }
        }
        slack[m].push_back(most);
      }
    }
    const double best = *std::max_element(slack[n - 1].begin(), slack[n - 1].end());
    if (!(best >= 0.0)) return best;
    // Pass 2: the least motion (sum of |dz| at the knots and of their changes) of a chain whose
    // every ease keeps the wanted slack, with each knot's predecessor for the way back.
    const double wanted = Keep(2.0 * best) - 1e-12;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> motion(n);
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> from(n);
    for (std::size_t m = 0; m < n; ++m) {
      for (const double b : heights[m]) {
        double least = m == 0 && std::min(b - windows[0].lo, windows[0].hi - b) >= wanted ? std::abs(b) : inf;
        std::pair<std::size_t, std::size_t> previous{n, 0};
        for (std::size_t k = 0; k < m; ++k) {
          for (std::size_t g = 0; g < heights[k].size(); ++g) {
            const double a = heights[k][g];
            const double cost = motion[k][g] + std::abs(b - a) + std::abs(b);
            if (cost >= least || ease_slack(k, a, m, b) < wanted) continue;
            least = cost;
            previous = {k, g};
          }
        }
        motion[m].push_back(least);
        from[m].push_back(previous);
      }
    }
    const auto last = std::min_element(motion[n - 1].begin(), motion[n - 1].end());
    chain.clear();
    for (std::pair<std::size_t, std::size_t> at{n - 1, static_cast<std::size_t>(last - motion[n - 1].begin())}; at.first < n;
         at = from[at.first][at.second]) {
      chain.push_back({times[at.first], dx, heights[at.first][at.second]});
    }
    std::reverse(chain.begin(), chain.end());
    return best;
  }

  // How far from the ends of a feasible range of this width the height is kept.
  double Keep(double width) const {
    return std::min(0.5 * width, std::max(settings_.height_margin, settings_.height_centering * width));
  }

  // Heights to try inside a window: evenly spaced, with no correction (clamped into it) among them.
  static std::vector<double> Grid(const Interval1& window) {
    constexpr int kPoints = 12;
    std::vector<double> values = {std::clamp(0.0, window.lo, window.hi)};
    for (int i = 0; i <= kPoints; ++i) values.push_back(window.lo + (window.hi - window.lo) * i / kPoints);
    return values;
  }

  StanceChecker checker_;
  const Staircase& stairs_;
  const std::vector<std::string>& legs_;
  const std::vector<Eigen::Vector3d>& initial_;
  const std::vector<Footstep>& footsteps_;
  const std::function<Eigen::Vector2d(double)>& com_target_;
  const BodyPathSettings& settings_;
  const std::vector<BodyState>& body_;
};

// The swings, overlapping ones merged, in time order.
std::vector<Segment> SwingSegments(const std::vector<Footstep>& footsteps) {
  std::vector<Segment> swings;
  for (const Footstep& f : footsteps) swings.push_back({f.t_liftoff, f.t_touchdown});
  std::sort(swings.begin(), swings.end(), [](const Segment& a, const Segment& b) { return a.t0 < b.t0; });
  std::vector<Segment> merged;
  for (const Segment& s : swings) {
    if (!merged.empty() && s.t0 <= merged.back().t1) {
      merged.back().t1 = std::max(merged.back().t1, s.t1);
    } else {
      merged.push_back(s);
    }
  }
  return merged;
}

// One component of the corrections eased between the keys that set it (zero velocity at each),
// held before the first and after the last.
double EasedAt(const std::vector<PostureKey>& keys, double t, double PostureKey::*value, bool with_repairs) {
  const PostureKey* before = nullptr;
  const PostureKey* after = nullptr;
  for (const PostureKey& k : keys) {
    if (k.repair && !with_repairs) continue;
    if (k.t <= t) {
      before = &k;
    } else {
      after = &k;
      break;
    }
  }
  if (before == nullptr) return after != nullptr ? after->*value : 0.0;
  if (after == nullptr) return before->*value;
  const double u = after->t > before->t ? SmoothStep((t - before->t) / (after->t - before->t)) : 0.0;
  return before->*value + u * (after->*value - before->*value);
}

// The corrections at t. The shift eases from one swing's key to the next in one go: a repair in
// between changes the height only, and were the shift to stop there as well, the body would halt
// and restart along the flight within the four-feet phase (the backward descent's body then
// accelerated at 15 m/s^2, more than its feet can carry).
PostureKey CorrectionAt(const std::vector<PostureKey>& keys, double t) {
  return {t, EasedAt(keys, t, &PostureKey::dx, false), EasedAt(keys, t, &PostureKey::dz, true)};
}

}  // namespace

void FitPosturesToStances(const RobotModel& robot, const Staircase& stairs, const std::vector<std::string>& legs,
                          const std::vector<Eigen::Vector3d>& initial, const std::vector<Footstep>& footsteps,
                          const std::function<Eigen::Vector2d(double)>& com_target, const BodyPathSettings& settings,
                          std::vector<BodyState>& body) {
  if (body.empty()) return;
  PostureFitter fitter(robot, stairs, legs, initial, footsteps, com_target, settings, body);
  std::vector<PostureKey> keys;
  const auto add = [&](const Segment& segment) { return fitter.Fit(segment, keys.empty() ? 0.0 : keys.back().dx, keys); };
  add({0.0, 0.0});
  std::vector<Segment> eases;  // from one swing's correction to the next one's, four feet down
  for (const Segment& swing : SwingSegments(footsteps)) {
    if (!keys.empty()) eases.push_back({keys.back().t, swing.t0});
    if (add(swing)) continue;
    // Nothing at one shift suits the whole swing: each instant of it gets its own. The body may
    // jump between them; the validator's body_acceleration check then rejects the plan.
    for (double t : fitter.KeyTimes(swing)) add({t, t});
  }
  // The instants of each ease are checked as well; where one leaves its feasible heights, a key
  // there puts it back (and the ease goes through it).
  for (const Segment& ease : eases) {
    for (double t : fitter.KeyTimes(ease)) {
      PostureKey repaired;
      const bool end = t <= ease.t0 + 1e-9 || t >= ease.t1 - 1e-9;  // the swings' own keys
      if (end || !fitter.Repair(t, CorrectionAt(keys, t), repaired)) continue;
      const auto at = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const PostureKey& k) { return v < k.t; });
      keys.insert(at, repaired);
    }
  }
  if (keys.empty()) return;
  for (BodyState& b : body) {
    const PostureKey c = CorrectionAt(keys, b.t);
    b.x += c.dx;
    b.z += c.dz;
  }
}

}  // namespace stairplan
