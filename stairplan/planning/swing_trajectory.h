// The path of a swinging foot from one foothold to the next: lift, travel, lower. It rises above
// everything the stairs put between the two footholds (treads and nosings) by a clearance, so the
// validator, the simulator and the drawings all move the foot the same way.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/staircase.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// 0 -> 1 as u goes 0 -> 1 (clamped), with zero slope at both ends: motions that start and stop smoothly.
double SmoothStep(double u);

/// The shape of a swing: clearance over the stairs and how it rises, travels and lowers.
struct SwingSettings {
  double clearance = 0.06;      ///< foot contact point above the highest obstacle on the way [m]
  double min_lift = 0.05;       ///< at least this far above the higher foothold [m]
  double lift_fraction = 0.25;  ///< share of the swing spent rising before moving forward
  double lower_fraction = 0.25; ///< share spent lowering after arriving above the target

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// One foot's swing: contact-point positions over the swing phase 0..1.
class SwingTrajectory {
 public:
  /// A swing from `from_W` to `to_W` clearing the highest obstacle of `stairs` between them.
  SwingTrajectory(const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, const Staircase& stairs,
                  const SwingSettings& settings = {});
  /// A swing with its apex given (as a plan states it), making `approach_share` of its horizontal
  /// travel low before it rises (Footstep::swing_approach_share; 0: it rises first).
  SwingTrajectory(const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, double apex_z,
                  const SwingSettings& settings = {}, double approach_share = 0.0);

  /// The foot's contact point at phase s in [0, 1] (clamped).
  Eigen::Vector3d At(double s) const;
  /// Height of the swing's top [m].
  double apex_z() const { return apex_z_; }

 private:
  Eigen::Vector3d from_, to_;
  double apex_z_ = 0.0;
  double approach_share_ = 0.0;
  SwingSettings settings_;
};

/// Where each foot (legs in `legs` order) is at time t: stance feet on their contact points, a
/// swinging foot at swing_at(its footstep, swing phase in [0, 1)). `in_stance`, when given, says
/// which feet are down. The walk FeetAlongSwings and the body path's FeetAt share.
std::vector<Eigen::Vector3d> FeetWhileSwinging(const std::vector<std::string>& legs,
                                               const std::vector<Eigen::Vector3d>& initial,
                                               const std::vector<Footstep>& footsteps, double t,
                                               const std::function<Eigen::Vector3d(const Footstep&, double)>& swing_at,
                                               std::vector<bool>* in_stance = nullptr);

/// Where each foot (legs in `legs` order) is at time t as a plan is executed: stance feet on their
/// contact points, swinging feet along their swing trajectories (the footstep's apex when it states
/// one, else the apex `stairs` ask for). `in_stance`, when given, says which feet are down.
std::vector<Eigen::Vector3d> FeetAlongSwings(const std::vector<std::string>& legs,
                                             const std::vector<Eigen::Vector3d>& initial,
                                             const std::vector<Footstep>& footsteps, double t, const Staircase& stairs,
                                             const SwingSettings& settings, std::vector<bool>* in_stance = nullptr);

/// The highest stair surface (with its nosing lip) under the segment from a to b in xy [m].
double HighestObstacleBetween(const Staircase& stairs, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

}  // namespace stairplan
