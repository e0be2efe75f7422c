#include "planning/body_path.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <urdf_model/model.h>

#include "geometry/field_error.h"
#include "collision/stance_check.h"
#include "planning/com_model.h"

namespace stairplan {
namespace {

double Smooth(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

struct Keyframe {
  double t;
  Eigen::Vector2d com_xy;
};

Eigen::Vector2d Centroid(const std::vector<Eigen::Vector3d>& feet, const std::vector<bool>& use) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (std::size_t i = 0; i < feet.size(); ++i) {
    if (!use[i]) continue;
    sum += feet[i].head<2>();
    ++n;
  }
  return n > 0 ? Eigen::Vector2d(sum / n) : sum;
}

// COM keyframes: at the start and end the centroid of all four feet; through each swing the
// centroid of the other three (blended by `shift` toward the four-foot centroid).
std::vector<Keyframe> ComKeyframes(const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& initial,
                                   const std::vector<Footstep>& steps, double shift) {
  const std::vector<bool> all(legs.size(), true);
  std::vector<Keyframe> keys = {{0.0, Centroid(initial, all)}};
  for (const Footstep& s : steps) {
    const double mid = 0.5 * (s.t_liftoff + s.t_touchdown);
    std::vector<bool> stance;
    const std::vector<Eigen::Vector3d> feet = FeetAt(legs, initial, steps, mid, &stance);
    const Eigen::Vector2d target = shift * Centroid(feet, stance) + (1.0 - shift) * Centroid(feet, all);
    keys.push_back({s.t_liftoff, target});
    keys.push_back({s.t_touchdown, target});
  }
  const double end = steps.empty() ? 0.0 : steps.back().t_touchdown;
  keys.push_back({end + 1e-9, Centroid(FeetAt(legs, initial, steps, end + 1.0), all)});
  return keys;
}

Eigen::Vector2d ComAt(const std::vector<Keyframe>& keys, double t) {
  const auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const Keyframe& k) { return v < k.t; });
  if (next == keys.begin()) return keys.front().com_xy;
  if (next == keys.end()) return keys.back().com_xy;
  const Keyframe& a = *(next - 1);
  const double u = next->t > a.t ? (t - a.t) / (next->t - a.t) : 1.0;
  return a.com_xy + Smooth(u) * (next->com_xy - a.com_xy);
}

// Moves the body horizontally until the COM of the posture (legs through IK) is at `target`.
void CorrectCom(const RobotKinematics& kinematics, const ComModel& com_model, RobotWorkspace& ws,
                const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& feet,
                const Eigen::Vector2d& target, int passes, BodyState& b) {
  for (int pass = 0; pass < passes; ++pass) {
    BodyPose pose;
    pose.position_W = {b.x, b.y, b.z};
    pose.pitch = b.pitch;
    pose.yaw = b.yaw;
    std::array<Eigen::Vector3d, 4> q;
    for (std::size_t i = 0; i < legs.size() && i < 4; ++i) {
      const int l = kinematics.LegIndex(legs[i]);
      const Eigen::Vector3d foot = feet[i] + Eigen::Vector3d(0.0, 0.0, kinematics.leg(l).model().foot_radius);
      q[static_cast<std::size_t>(l)] = kinematics.SolveFootIkWorld(l, foot, pose, ws).q;
    }
    const Eigen::Vector3d com = com_model.Com(pose, q, ws);
    b.x -= com.x() - target.x();
    b.y -= com.y() - target.y();
  }
}

// A posture correction at one instant: a shift along the flight and a height change.
struct PostureKey {
  double t = 0.0;
  double dx = 0.0;
  double dz = 0.0;
};

// The feasible body heights at one instant with the body shifted by dx along the flight.
Interval1 HeightWindow(StanceChecker& checker, const std::array<Eigen::Vector3d, 4>& contacts, BodyPose pose, double dx) {
  pose.position_W.x() += dx;
  const double z = pose.position_W.z();
  return checker.FeasibleBodyHeights(pose, contacts, z - 0.2, z + 0.1, 0.02, 0.004);
}

// The correction that puts the posture at one instant (swing feet where their swings are) inside
// its feasible height range, kept height_centering of the range's width from either end. When the
// range at the planned position is narrow, shifts along the flight that keep the COM target
// `shift_margin` inside the support polygon are tried and the widest range wins. False when no
// posture is feasible (a swing foot grazing its tread, or a posture nothing here repairs).
bool FitPosture(StanceChecker& checker, const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& feet,
                const std::vector<bool>& stance, const BodyPose& pose, const Eigen::Vector2d& com,
                const BodyPathSettings& settings, PostureKey& key) {
  std::array<Eigen::Vector3d, 4> contacts;
  std::vector<Eigen::Vector2d> support;
  for (std::size_t i = 0; i < legs.size() && i < 4; ++i) {
    contacts[static_cast<std::size_t>(checker.kinematics().LegIndex(legs[i]))] = feet[i];
    if (stance[i]) support.push_back(feet[i].head<2>());
  }
  const Polygon2 polygon = ConvexHull(support);
  Interval1 best;
  const int shifts = static_cast<int>(std::floor(settings.max_shift / settings.shift_step + 1e-9));
  for (int k = 0; k <= 2 * shifts; ++k) {
    const double dx = (k % 2 == 0 ? -1.0 : 1.0) * ((k + 1) / 2) * settings.shift_step;  // 0, +s, -s, +2s, ...
    if (k > 0 && -polygon.SignedDistance(com + Eigen::Vector2d(dx, 0.0)) < settings.shift_margin) continue;
    const Interval1 window = HeightWindow(checker, contacts, pose, dx);
    if (window.empty() || (!best.empty() && window.hi - window.lo <= best.hi - best.lo)) continue;
    best = window;
    key.dx = dx;
    if (best.hi - best.lo >= settings.wide_height_range) break;
  }
  if (best.empty()) return false;
  const double z = pose.position_W.z(), width = best.hi - best.lo;
  const double keep = std::min(0.5 * width, std::max(settings.height_margin, settings.height_centering * width));
  key.dz = std::clamp(z, best.lo + keep, best.hi - keep) - z;
  return true;
}

// The instants at which the height is fitted: the start, every liftoff and touchdown, and every
// height_key_period in between.
std::vector<double> HeightKeyTimes(const std::vector<Footstep>& footsteps, double duration, double period) {
  std::vector<double> times = {0.0};
  for (const Footstep& f : footsteps) {
    times.push_back(f.t_liftoff);
    times.push_back(f.t_touchdown);
  }
  const int count = static_cast<int>(std::floor(duration / period));
  for (int k = 1; k <= count; ++k) times.push_back(k * period);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [](double a, double b) { return b - a < 1e-6; }), times.end());
  return times;
}

// The key corrections interpolated linearly in time (held before the first and after the last).
PostureKey CorrectionAt(const std::vector<PostureKey>& keys, double t) {
  const auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const PostureKey& k) { return v < k.t; });
  if (next == keys.begin()) return keys.front();
  if (next == keys.end()) return keys.back();
  const PostureKey& a = *(next - 1);
  const double u = next->t > a.t ? (t - a.t) / (next->t - a.t) : 0.0;
  return {t, a.dx + u * (next->dx - a.dx), a.dz + u * (next->dz - a.dz)};
}

// Postures fitted at the key instants (FitPosture), the corrections interpolated between them.
void FitPosturesToStances(const RobotModel& robot, const Staircase& stairs, const std::vector<std::string>& legs,
                          const std::vector<Eigen::Vector3d>& initial, const std::vector<Footstep>& footsteps,
                          const std::vector<Keyframe>& com_keys, const BodyPathSettings& settings,
                          std::vector<BodyState>& body) {
  StanceSettings stance_settings;
  stance_settings.min_clearance = settings.touchdown_clearance;
  StanceChecker checker(robot, stairs, stance_settings);
  std::vector<PostureKey> keys;
  const double duration = body.empty() ? 0.0 : body.back().t;
  for (double t : HeightKeyTimes(footsteps, duration, settings.height_key_period)) {
    std::vector<bool> stance;
    const std::vector<Eigen::Vector3d> feet = FeetAlongSwings(legs, initial, footsteps, t, stairs, settings.swing, &stance);
    PostureKey key{t, 0.0, 0.0};
    if (FitPosture(checker, legs, feet, stance, BodyPoseAt(body, t), ComAt(com_keys, t), settings, key)) keys.push_back(key);
  }
  if (keys.empty()) return;
  for (BodyState& b : body) {
    const PostureKey c = CorrectionAt(keys, b.t);
    b.x += c.dx;
    b.z += c.dz;
  }
}

}  // namespace

BodyPose BodyPoseAt(const std::vector<BodyState>& body, double t) {
  BodyPose pose;
  if (body.empty()) return pose;
  const auto next = std::upper_bound(body.begin(), body.end(), t, [](double v, const BodyState& b) { return v < b.t; });
  const BodyState& a = next == body.begin() ? body.front() : *(next - 1);
  const BodyState& b = next == body.end() ? body.back() : *next;
  const double u = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
  pose.position_W = {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.z + u * (b.z - a.z)};
  pose.pitch = a.pitch + u * (b.pitch - a.pitch);
  pose.yaw = a.yaw + u * (b.yaw - a.yaw);
  return pose;
}

void BodyPathSettings::Validate() const {
  RequireInRange("hip_height_fraction", hip_height_fraction, 0.05, 1.0);
  RequireInRange("sample_period", sample_period, 1e-3, 1.0);
  RequireInRange("stability_shift", stability_shift, 0.0, 1.0);
  RequireInRange("pitch_fraction", pitch_fraction, 0.0, 1.0);
  RequireInRange("touchdown_clearance", touchdown_clearance, -1.0, 0.1);
  RequireInRange("height_margin", height_margin, 0.0, 0.1);
  RequireInRange("height_centering", height_centering, 0.0, 0.5);
  RequireInRange("height_key_period", height_key_period, 0.01, 10.0);
  RequireInRange("wide_height_range", wide_height_range, 0.0, 1.0);
  RequireInRange("max_shift", max_shift, 0.0, 0.5);
  RequireInRange("shift_step", shift_step, 0.005, 0.5);
  RequireInRange("shift_margin", shift_margin, 0.0, 0.5);
  swing.Validate();
  if (com_passes < 0 || com_passes > 10) throw FieldError("com_passes", "must be from 0 to 10");
}

Eigen::Vector3d ApproximateComOffset(const RobotModel& robot) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (const LegModel& leg : robot.legs()) {
    sum += leg.mass * leg.hip_B;
    mass += leg.mass;
  }
  // Everything not in a leg is lumped at the base link's own centre of mass.
  const double base_mass = std::max(0.0, robot.total_mass() - mass);
  const urdf::LinkConstSharedPtr base = robot.urdf().getLink(robot.base_link());
  if (base && base->inertial) {
    const urdf::Vector3& p = base->inertial->origin.position;
    sum += base_mass * Eigen::Vector3d(p.x, p.y, p.z);
  }
  return mass + base_mass > 0.0 ? Eigen::Vector3d(sum / (mass + base_mass)) : Eigen::Vector3d::Zero();
}

std::vector<Eigen::Vector3d> FeetAt(const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& initial,
                                    const std::vector<Footstep>& footsteps, double t, std::vector<bool>* in_stance) {
  std::vector<Eigen::Vector3d> feet = initial;
  if (in_stance != nullptr) in_stance->assign(legs.size(), true);
  for (const Footstep& s : footsteps) {
    if (s.t_liftoff >= t) continue;
    const auto leg = static_cast<std::size_t>(std::find(legs.begin(), legs.end(), s.leg) - legs.begin());
    if (leg >= legs.size()) continue;
    if (t >= s.t_touchdown) {
      feet[leg] = s.position_W;
    } else {
      const double u = (t - s.t_liftoff) / (s.t_touchdown - s.t_liftoff);
      feet[leg] = s.from_W + u * (s.position_W - s.from_W);
      if (in_stance != nullptr) (*in_stance)[leg] = false;
    }
  }
  return feet;
}

std::vector<BodyState> BodyPathForFootsteps(const RobotModel& robot, const std::vector<std::string>& legs,
                                            const std::vector<Eigen::Vector3d>& initial_feet,
                                            const std::vector<Footstep>& footsteps, double yaw,
                                            const BodyPathSettings& settings, const Staircase* stairs) {
  settings.Validate();
  const RobotKinematics kinematics(robot);
  const ComModel com_model(kinematics);
  RobotWorkspace ws(kinematics);
  double reach = 0.0, hip_z = 0.0, foot_radius = 0.0;
  for (const LegKinematics& leg : kinematics.legs()) {
    reach += leg.reach().hi / 4.0;  // the reach the joint limits allow, not the sum of the links
    hip_z += leg.hip_B().z() / 4.0;
    foot_radius += leg.model().foot_radius / 4.0;
  }
  const double hip_height = settings.hip_height_fraction * reach;
  const Eigen::Vector3d com_B = ApproximateComOffset(robot);
  const Eigen::Vector2d com_offset_W = Eigen::Rotation2Dd(yaw) * com_B.head<2>();
  const std::vector<Keyframe> keys = ComKeyframes(legs, initial_feet, footsteps, settings.stability_shift);
  const double duration = footsteps.empty() ? 0.0 : footsteps.back().t_touchdown;
  const int samples = static_cast<int>(std::ceil(duration / settings.sample_period - 1e-9));
  std::vector<BodyState> body;
  for (int s = 0; s <= samples; ++s) {
    const double t = std::min(duration, s * settings.sample_period);
    const std::vector<Eigen::Vector3d> feet = FeetAt(legs, initial_feet, footsteps, t);
    double sum_z = 0.0, front_x = 0.0, front_z = 0.0, hind_x = 0.0, hind_z = 0.0;
    Eigen::Vector2d feet_xy = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < feet.size(); ++i) {
      sum_z += feet[i].z() / 4.0;
      feet_xy += feet[i].head<2>() / 4.0;
      const bool front = robot.leg(legs[i]).hip_B.x() > 0.0;
      (front ? front_x : hind_x) += feet[i].x() / 2.0;
      (front ? front_z : hind_z) += feet[i].z() / 2.0;
    }
    BodyState b;
    b.t = t;
    const Eigen::Vector2d com = ComAt(keys, t);
    b.x = com.x() - com_offset_W.x();
    b.y = com.y() - com_offset_W.y();
    b.z = sum_z + foot_radius + hip_height - hip_z;
    b.yaw = yaw;
    b.pitch = -settings.pitch_fraction * std::atan2(front_z - hind_z, (front_x - hind_x) * std::cos(yaw));
    b.com_shift = (com - feet_xy).dot(Eigen::Vector2d(std::cos(yaw), std::sin(yaw)));
    CorrectCom(kinematics, com_model, ws, legs, feet, com, settings.com_passes, b);
    body.push_back(b);
  }
  if (stairs != nullptr && settings.touchdown_clearance >= 0.0) {
    FitPosturesToStances(robot, *stairs, legs, initial_feet, footsteps, keys, settings, body);
  }
  return body;
}

}  // namespace stairplan
