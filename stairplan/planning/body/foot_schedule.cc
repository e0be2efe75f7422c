#include "stairplan/planning/body/foot_schedule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace stairplan {

FootSchedule::FootSchedule(const RobotModel& robot, const Plan& plan, const Staircase* stairs,
                           const SwingSettings& swing) {
  const auto& models = robot.legs();
  if (plan.initial_feet_W.size() != plan.legs.size() || plan.legs.size() != models.size()) {
    throw std::invalid_argument("FootSchedule: the plan's legs and initial_feet_W must match the robot's " +
                                std::to_string(models.size()) + " legs");
  }
  yaw_ = plan.facing == Facing::kForward ? 0.0 : M_PI;
  heading_ = plan.facing == Facing::kForward ? 1.0 : -1.0;
  legs_.resize(models.size());
  const auto leg_index = [&](const std::string& name, const std::string& what) {
    for (std::size_t i = 0; i < models.size(); ++i) {
      if (models[i].name == name) return static_cast<int>(i);
    }
    throw std::invalid_argument("FootSchedule: " + what + " names an unknown leg '" + name + "'");
  };
  for (std::size_t p = 0; p < plan.legs.size(); ++p) {
    const int l = leg_index(plan.legs[p], "plan.legs[" + std::to_string(p) + "]");
    if (!plan.initial_feet_W[p].allFinite()) {
      throw std::invalid_argument("FootSchedule: initial_feet_W[" + std::to_string(p) + "] is not finite");
    }
    LegTimeline& tl = legs_[static_cast<std::size_t>(l)];
    const LegModel& m = models[static_cast<std::size_t>(l)];
    tl.offset_W = Eigen::Vector2d(heading_ * m.hip_B.x(), heading_ * m.foot_zero_B.y());
    tl.front = m.hip_B.x() > 0.0;
    tl.footholds.push_back(static_cast<int>(footholds_.size()));
    footholds_.push_back({l, plan.initial_feet_W[p], -1});
  }
  for (std::size_t i = 0; i < plan.footsteps.size(); ++i) {
    const Footstep& f = plan.footsteps[i];
    const std::string what = "footsteps[" + std::to_string(i) + "]";
    const int l = leg_index(f.leg, what);
    if (!std::isfinite(f.t_liftoff) || !std::isfinite(f.t_touchdown) || f.t_touchdown < f.t_liftoff ||
        !f.position_W.allFinite()) {
      throw std::invalid_argument("FootSchedule: " + what + " has non-finite or reversed times or position");
    }
    LegTimeline& tl = legs_[static_cast<std::size_t>(l)];
    if (!tl.touchdowns.empty() && f.t_liftoff < tl.touchdowns.back()) {
      throw std::invalid_argument("FootSchedule: " + what + " lifts off before the leg's previous touchdown");
    }
    tl.liftoffs.push_back(f.t_liftoff);
    tl.touchdowns.push_back(f.t_touchdown);
    const Eigen::Vector3d& from = footholds_[static_cast<std::size_t>(tl.footholds.back())].contact_W;
    if (std::isfinite(f.swing_apex_z)) {
      tl.swings.emplace_back(from, f.position_W, f.swing_apex_z, swing);
    } else if (stairs != nullptr) {
      tl.swings.emplace_back(from, f.position_W, *stairs, swing);
    } else {
      tl.swings.emplace_back(from, f.position_W, std::max(from.z(), f.position_W.z()) + swing.min_lift, swing);
    }
    tl.footholds.push_back(static_cast<int>(footholds_.size()));
    footholds_.push_back({l, f.position_W, f.stair_index});
    end_time_ = std::max(end_time_, f.t_touchdown);
  }
  if (!plan.body.empty()) end_time_ = std::max(end_time_, plan.body.back().t);
  PrepareNeutral();
}

LegPhase FootSchedule::Phase(int leg, double t) const {
  const LegTimeline& tl = legs_[static_cast<std::size_t>(leg)];
  LegPhase phase;
  // j: swings that have started by t.
  const auto j = static_cast<std::size_t>(std::upper_bound(tl.liftoffs.begin(), tl.liftoffs.end(), t) - tl.liftoffs.begin());
  if (j > 0 && t < tl.touchdowns[j - 1]) {
    const double span = tl.touchdowns[j - 1] - tl.liftoffs[j - 1];
    phase.stance = false;
    phase.foothold = tl.footholds[j - 1];
    phase.next_foothold = tl.footholds[j];
    phase.progress = span > 0.0 ? std::clamp((t - tl.liftoffs[j - 1]) / span, 0.0, 1.0) : 1.0;
    phase.t_liftoff = tl.liftoffs[j - 1];
    phase.t_touchdown = tl.touchdowns[j - 1];
    const Eigen::Vector3d& a = footholds_[static_cast<std::size_t>(phase.foothold)].contact_W;
    const Eigen::Vector3d& b = footholds_[static_cast<std::size_t>(phase.next_foothold)].contact_W;
    phase.foot_W = (1.0 - phase.progress) * a + phase.progress * b;
    phase.swing = static_cast<int>(j - 1);
    return phase;
  }
  phase.stance = true;
  phase.foothold = tl.footholds[j];
  phase.next_foothold = j + 1 < tl.footholds.size() ? tl.footholds[j + 1] : -1;
  phase.t_liftoff = j < tl.liftoffs.size() ? tl.liftoffs[j] : std::numeric_limits<double>::infinity();
  phase.t_touchdown = j > 0 ? tl.touchdowns[j - 1] : 0.0;
  phase.foot_W = footholds_[static_cast<std::size_t>(phase.foothold)].contact_W;
  return phase;
}

Eigen::Vector3d FootSchedule::SwingFoot(int leg, const LegPhase& phase) const {
  if (phase.stance || phase.swing < 0) return phase.foot_W;
  return legs_[static_cast<std::size_t>(leg)].swings[static_cast<std::size_t>(phase.swing)].At(phase.progress);
}

Eigen::Vector2d FootSchedule::FeetCentreXY(double t) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int l = 0; l < leg_count(); ++l) {
    sum += Phase(l, t).foot_W.head<2>() - legs_[static_cast<std::size_t>(l)].offset_W;
  }
  return sum / static_cast<double>(std::max(1, leg_count()));
}

Eigen::Vector2d FootSchedule::NeutralBodyXY(double t) const {
  if (!(smoothing_window_ > 0.0)) return FeetCentreXY(t);
  const double half = 0.5 * smoothing_window_;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int l = 0; l < leg_count(); ++l) {
    sum += (FootIntegral(l, t + half) - FootIntegral(l, t - half)) / smoothing_window_ - legs_[static_cast<std::size_t>(l)].offset_W;
  }
  return sum / static_cast<double>(std::max(1, leg_count()));
}

Eigen::Vector2d FootSchedule::FootholdXY(int leg, std::size_t j) const {
  const int f = legs_[static_cast<std::size_t>(leg)].footholds[j];
  return footholds_[static_cast<std::size_t>(f)].contact_W.head<2>();
}

Eigen::Vector2d FootSchedule::FootIntegral(int leg, double t) const {
  const LegTimeline& tl = legs_[static_cast<std::size_t>(leg)];
  const auto j = static_cast<std::size_t>(std::upper_bound(tl.liftoffs.begin(), tl.liftoffs.end(), t) - tl.liftoffs.begin());
  if (j > 0 && t < tl.touchdowns[j - 1]) {  // in swing j - 1: linear from one foothold to the next
    const double tau = t - tl.liftoffs[j - 1], span = tl.touchdowns[j - 1] - tl.liftoffs[j - 1];
    const Eigen::Vector2d a = FootholdXY(leg, j - 1);
    return tl.integral_at_liftoff[j - 1] + tau * a + 0.5 * tau * tau / span * (FootholdXY(leg, j) - a);
  }
  if (j == 0) return t * FootholdXY(leg, 0);
  return tl.integral_at_touchdown[j - 1] + (t - tl.touchdowns[j - 1]) * FootholdXY(leg, j);
}

void FootSchedule::PrepareNeutral() {
  std::vector<double> swings;
  for (int l = 0; l < leg_count(); ++l) {
    LegTimeline& tl = legs_[static_cast<std::size_t>(l)];
    const std::size_t count = tl.liftoffs.size();
    tl.integral_at_liftoff.resize(count);
    tl.integral_at_touchdown.resize(count);
    Eigen::Vector2d at = count == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(tl.liftoffs[0] * FootholdXY(l, 0));
    for (std::size_t j = 0; j < count; ++j) {
      if (j > 0) at += (tl.liftoffs[j] - tl.touchdowns[j - 1]) * FootholdXY(l, j);
      tl.integral_at_liftoff[j] = at;
      at += 0.5 * (tl.touchdowns[j] - tl.liftoffs[j]) * (FootholdXY(l, j) + FootholdXY(l, j + 1));
      tl.integral_at_touchdown[j] = at;
      swings.push_back(tl.touchdowns[j] - tl.liftoffs[j]);
    }
  }
  if (swings.empty()) return;
  std::nth_element(swings.begin(), swings.begin() + static_cast<std::ptrdiff_t>(swings.size() / 2), swings.end());
  smoothing_window_ = swings[swings.size() / 2];
}

template <typename FootAt>
double FootSchedule::FeetPitchOf(const FootAt& foot_W) const {
  double front_x = 0.0, front_z = 0.0, hind_x = 0.0, hind_z = 0.0;
  int fronts = 0, hinds = 0;
  for (int l = 0; l < leg_count(); ++l) {
    const Eigen::Vector3d p = foot_W(l);
    if (legs_[static_cast<std::size_t>(l)].front) {
      front_x += p.x(), front_z += p.z(), ++fronts;
    } else {
      hind_x += p.x(), hind_z += p.z(), ++hinds;
    }
  }
  if (fronts == 0 || hinds == 0) return 0.0;
  const double run = (front_x / fronts - hind_x / hinds) * heading_;
  if (!(run > 1e-6)) return 0.0;
  return -std::atan2(front_z / fronts - hind_z / hinds, run);
}

double FootSchedule::FeetPitch(double t) const {
  return FeetPitchOf([&](int l) { return Phase(l, t).foot_W; });
}

double FootSchedule::FeetPitch(const LegPhase* phases) const {
  return FeetPitchOf([&](int l) -> const Eigen::Vector3d& { return phases[l].foot_W; });
}

}  // namespace stairplan
