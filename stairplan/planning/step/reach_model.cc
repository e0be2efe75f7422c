#include "stairplan/planning/step/reach_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace stairplan {

GeometricReachModel::GeometricReachModel(double min_fraction, double max_fraction)
    : min_fraction_(min_fraction), max_fraction_(max_fraction) {
  if (!std::isfinite(min_fraction) || min_fraction < 0.0 || min_fraction >= 1.0) {
    throw std::invalid_argument("GeometricReachModel: min_fraction must be in [0, 1) (got " + std::to_string(min_fraction) + ")");
  }
  if (!std::isfinite(max_fraction) || max_fraction <= min_fraction || max_fraction > 1.0) {
    throw std::invalid_argument("GeometricReachModel: max_fraction must be in (min_fraction, 1] (got " +
                                std::to_string(max_fraction) + ")");
  }
}

double GeometricReachModel::Extension(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) {
  if (!(leg.max_reach > 0.0)) return std::numeric_limits<double>::infinity();
  return (foot_W - base_W * leg.hip_B).norm() / leg.max_reach;
}

bool GeometricReachModel::Reachable(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const {
  const double e = Extension(leg, base_W, foot_W);
  return e >= min_fraction_ && e <= max_fraction_;
}

double GeometricReachModel::Effort(const LegModel& leg, const Eigen::Isometry3d& base_W, const Eigen::Vector3d& foot_W) const {
  const double middle = 0.5 * (min_fraction_ + max_fraction_);
  return std::abs(Extension(leg, base_W, foot_W) - middle) / (0.5 * (max_fraction_ - min_fraction_));
}

}  // namespace stairplan
