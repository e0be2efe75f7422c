// Whether a leg reaches a foothold: a small interface so that the step planner can use the
// geometric bound below now and an IK-based check (stairplan/kinematics/) later without changing.
#pragma once

#include <Eigen/Geometry>

#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

/// Answers reach queries for one robot. Implementations must not allocate: the step planner calls
/// them in its per-cycle update.
class ReachModel {
 public:
  virtual ~ReachModel() = default;
  /// True when `leg` can put its foot centre at foot_W with the base at base_W (base frame to world).
  virtual bool Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const = 0;
  /// How far into its range the placement pushes the leg, 0 (relaxed) to 1 (at a limit); used as a
  /// soft cost. The default: 0 when reachable, 1 when not.
  virtual double Effort(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const {
    return Reachable(leg, base_W, foot_W) ? 0.0 : 1.0;
  }
};

/// The geometric bound from the LegModel: the hip-to-foot-centre distance lies within
/// [min_fraction, max_fraction] of the leg's max_reach.
class GeometricReachModel final : public ReachModel {
 public:
  /// Throws std::invalid_argument naming the fraction unless 0 <= min_fraction < max_fraction <= 1.
  explicit GeometricReachModel(double min_fraction = 0.30, double max_fraction = 0.95);

  bool Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const override;
  /// 0 at the middle of the band, 1 at either end, above 1 outside it.
  double Effort(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const override;
  /// The hip-to-foot distance as a fraction of max_reach.
  static double Extension(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W);

  /// Lower end of the reach band, as a fraction of max_reach.
  double min_fraction() const { return min_fraction_; }
  /// Upper end of the reach band, as a fraction of max_reach.
  double max_fraction() const { return max_fraction_; }

 private:
  double min_fraction_;
  double max_fraction_;
};

}  // namespace stairplan
