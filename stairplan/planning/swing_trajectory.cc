#include "stairplan/planning/swing_trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "stairplan/geometry/field_error.h"

namespace stairplan {

double SmoothStep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

void SwingSettings::Validate() const {
  RequireInRange("clearance", clearance, 0.0, 1.0);
  RequireInRange("min_lift", min_lift, 0.0, 1.0);
  RequireInRange("lift_fraction", lift_fraction, 0.01, 0.49);
  RequireInRange("lower_fraction", lower_fraction, 0.01, 0.49);
}

double HighestObstacleBetween(const Staircase& stairs, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double x_lo = std::min(a.x(), b.x()), x_hi = std::max(a.x(), b.x());
  double highest = -std::numeric_limits<double>::infinity();
  for (const Box3& box : stairs.Solids()) {
    if (box.max.x() < x_lo || box.min.x() > x_hi) continue;
    highest = std::max(highest, box.max.z());
  }
  return std::isfinite(highest) ? highest : std::max(stairs.HeightAt(a.x(), a.y()), stairs.HeightAt(b.x(), b.y()));
}

SwingTrajectory::SwingTrajectory(const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, const Staircase& stairs,
                                 const SwingSettings& settings)
    : from_(from_W), to_(to_W), settings_(settings) {
  settings_.Validate();
  const double obstacle = HighestObstacleBetween(stairs, from_W.head<2>(), to_W.head<2>());
  apex_z_ = std::max(obstacle + settings_.clearance, std::max(from_W.z(), to_W.z()) + settings_.min_lift);
}

SwingTrajectory::SwingTrajectory(const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, double apex_z,
                                 const SwingSettings& settings, double approach_share)
    : from_(from_W), to_(to_W), apex_z_(apex_z), approach_share_(approach_share), settings_(settings) {
  settings_.Validate();
  if (!std::isfinite(apex_z) || !from_W.allFinite() || !to_W.allFinite()) {
    throw std::invalid_argument("SwingTrajectory: non-finite footholds or apex");
  }
  if (!(approach_share >= 0.0 && approach_share < 1.0)) throw std::invalid_argument("SwingTrajectory: approach_share must be in [0, 1)");
}

Eigen::Vector3d SwingTrajectory::At(double s) const {
  s = std::clamp(s, 0.0, 1.0);
  const double rise_end = settings_.lift_fraction, lower_start = 1.0 - settings_.lower_fraction;
  // Horizontal travel beyond approach_share only between the rise and the descent, so the foot
  // never sweeps a nosing. The approach takes the first half of the rise, low over the foothold
  // it leaves (a tenth of the rise); the second half rises straight up.
  const double u = s / rise_end;
  const double approach = approach_share_ > 0.0 ? SmoothStep(2.0 * u) : 0.0;
  const double climb = approach_share_ > 0.0 ? 0.1 * approach + 0.9 * SmoothStep(2.0 * u - 1.0) : SmoothStep(u);
  const double travel = s <= rise_end ? approach_share_ * approach
                                      : approach_share_ + (1.0 - approach_share_) * SmoothStep((s - rise_end) / (lower_start - rise_end));
  Eigen::Vector3d p = from_ + travel * (to_ - from_);
  if (s <= rise_end) {
    p.z() = from_.z() + climb * (apex_z_ - from_.z());
  } else if (s >= lower_start) {
    p.z() = apex_z_ + SmoothStep((s - lower_start) / settings_.lower_fraction) * (to_.z() - apex_z_);
  } else {
    p.z() = apex_z_;
  }
  return p;
}

}  // namespace stairplan

namespace stairplan {

std::vector<Eigen::Vector3d> FeetWhileSwinging(const std::vector<std::string>& legs,
                                               const std::vector<Eigen::Vector3d>& initial,
                                               const std::vector<Footstep>& footsteps, double t,
                                               const std::function<Eigen::Vector3d(const Footstep&, double)>& swing_at,
                                               std::vector<bool>* in_stance) {
  std::vector<Eigen::Vector3d> feet = initial;
  if (in_stance != nullptr) in_stance->assign(legs.size(), true);
  for (const Footstep& f : footsteps) {
    if (f.t_liftoff >= t) continue;
    const auto leg = static_cast<std::size_t>(std::find(legs.begin(), legs.end(), f.leg) - legs.begin());
    if (leg >= legs.size()) continue;
    if (t >= f.t_touchdown) {
      feet[leg] = f.position_W;
      continue;
    }
    feet[leg] = swing_at(f, (t - f.t_liftoff) / (f.t_touchdown - f.t_liftoff));
    if (in_stance != nullptr) (*in_stance)[leg] = false;
  }
  return feet;
}

std::vector<Eigen::Vector3d> FeetAlongSwings(const std::vector<std::string>& legs,
                                             const std::vector<Eigen::Vector3d>& initial,
                                             const std::vector<Footstep>& footsteps, double t, const Staircase& stairs,
                                             const SwingSettings& settings, std::vector<bool>* in_stance) {
  const auto along_swing = [&](const Footstep& f, double phase) {
    const SwingTrajectory swing = std::isfinite(f.swing_apex_z)
                                      ? SwingTrajectory(f.from_W, f.position_W, f.swing_apex_z, settings, f.swing_approach_share)
                                      : SwingTrajectory(f.from_W, f.position_W, stairs, settings);
    return swing.At(phase);
  };
  return FeetWhileSwinging(legs, initial, footsteps, t, along_swing, in_stance);
}

}  // namespace stairplan
