#include "stairplan/simulation/impact_detection.h"

#include <algorithm>
#include <cmath>

#include "stairplan/geometry/field_error.h"

namespace stairplan {

const char* ToString(ImpactSource source) {
  switch (source) {
    case ImpactSource::kNone: return "none";
    case ImpactSource::kContacts: return "contacts";
    case ImpactSource::kTorqueResidual: return "torque_residual";
  }
  return "unknown";
}

void ImpactDetectionSettings::Validate() const {
  RequireInRange("impact.force_threshold", force_threshold, 1e-3, 10.0);
  RequireInRange("impact.scuff_phase", scuff_phase, 0.0, 1.0);
  RequireInRange("impact.min_reswing_time", min_reswing_time, 0.0, 5.0);
  RequireInRange("impact.leg_strike_distance", leg_strike_distance, 0.0, 0.5);
  RequireInRange("impact.near_stairs", near_stairs, 0.0, 0.5);
  RequireInRange("impact.touchdown_clearance", touchdown_clearance, 0.0, 0.5);
  RequireInRange("impact.retract_distance", retract_distance, 0.0, 0.5);
  RequireInRange("impact.hop_time", hop_time, 0.01, 5.0);
  response.Validate();
}

std::optional<ImpactKind> ClassifySwingFootForce(const Eigen::Vector3d& force_W, const Eigen::Vector3d& swing_dir_W,
                                                 double phase, double touchdown_phase, double threshold_n,
                                                 double scuff_phase) {
  if (!(force_W.norm() > threshold_n)) return std::nullopt;
  if (phase < scuff_phase) return ImpactKind::kLiftoffScuff;
  const Eigen::Vector2d dir = swing_dir_W.head<2>().norm() > 1e-9 ? swing_dir_W.head<2>().normalized() : Eigen::Vector2d::Zero();
  const double against = -force_W.head<2>().dot(dir);  // pushing the foot back along its swing
  const bool upward = force_W.z() > 0.0 && force_W.z() >= std::max(against, 0.0);
  if (upward && phase >= touchdown_phase) return ImpactKind::kTouchdown;
  return ImpactKind::kTrip;
}

ImpactKind ClassifyLegLinkOnStairs(const Eigen::Vector3d& contact_W, const Eigen::Vector3d& hip_W, double body_yaw) {
  const Eigen::Vector2d heading(std::cos(body_yaw), std::sin(body_yaw));
  return (contact_W - hip_W).head<2>().dot(heading) < 0.0 ? ImpactKind::kKneeBehindBody : ImpactKind::kKneeGlancingTerrain;
}

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

bool InStepRegionAt(const ConstrainedMap& map, const Eigen::Vector3d& p_W) {
  const int stair = map.StairAt(p_W.head<2>());
  return stair >= 0 && std::abs(map.stair(stair).z - p_W.z()) < 0.02 && map.InStepRegion(stair, p_W.head<2>(), 1e-6);
}

ImpactKind ClassifyContralateral(const Eigen::Vector3d& swing_foot_W, const Eigen::Vector3d& contralateral_foot_W,
                                 bool swing_leg_left, double body_yaw) {
  const Eigen::Vector2d left(-std::sin(body_yaw), std::cos(body_yaw));
  const double beyond = (swing_foot_W - contralateral_foot_W).head<2>().dot(left) * (swing_leg_left ? -1.0 : 1.0);
  return beyond > 0.0 ? ImpactKind::kContralateralCrossing : ImpactKind::kContralateralStrike;
}

}  // namespace stairplan
