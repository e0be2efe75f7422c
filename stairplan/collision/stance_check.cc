#include "stairplan/collision/stance_check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stairplan {

const char* ToString(StanceStatus status) {
  switch (status) {
    case StanceStatus::kOk: return "ok";
    case StanceStatus::kOutOfReach: return "out_of_reach";
    case StanceStatus::kJointLimits: return "joint_limits";
    case StanceStatus::kCollision: return "collision";
  }
  return "unknown";
}

void StanceSettings::Validate() const {
  ik.Validate();
  if (!std::isfinite(min_clearance)) throw std::invalid_argument("StanceSettings.min_clearance: must be finite");
  if (!std::isfinite(clearance.support_tolerance) || clearance.support_tolerance < 0.0) {
    throw std::invalid_argument("StanceSettings.clearance.support_tolerance: must be a non-negative number");
  }
}

bool FootGrazesTread(const RobotCollisionModel& robot, int leg, const Clearance& stairs) {
  constexpr double kTouchTolerance = 1e-4;  // a foot sphere this deep in its tread still only touches [m]
  if (stairs.shape < 0 || stairs.part != StairPart::kTread) return false;
  const auto& shapes = robot.leg_shapes(leg);
  return shapes.at(static_cast<std::size_t>(stairs.shape)).foot_contact && stairs.distance > -kTouchTolerance;
}

Eigen::Vector3d FootOriginForContact(const LegModel& leg, const Eigen::Vector3d& contact_W,
                                     const Eigen::Matrix3d& foot_rotation_W) {
  const Eigen::Vector3d centre_W = contact_W + Eigen::Vector3d(0.0, 0.0, leg.foot_radius);
  return centre_W - foot_rotation_W * leg.foot_sphere_center;
}

NominalStance NominalStanceAt(const RobotKinematics& kinematics, RobotWorkspace& ws, double x) {
  NominalStance stance;
  // Where each foot's contact sphere touches down, in the base frame.
  const auto contact_B = [&](int l) -> Eigen::Vector3d {
    const LegKinematics& leg = kinematics.leg(l);
    return leg.FootPose(leg.nominal(), ws.leg(l)) * leg.model().foot_sphere_center -
           leg.model().foot_radius * Eigen::Vector3d::UnitZ();
  };
  stance.body.position_W = {x, 0.0, -contact_B(0).z()};
  for (int l = 0; l < 4; ++l) stance.contacts_W[static_cast<std::size_t>(l)] = stance.body.ToIsometry() * contact_B(l);
  return stance;
}

IkResult SolveContactIk(const LegKinematics& leg, const Eigen::Vector3d& contact_W, const Eigen::Isometry3d& body_W,
                        const Eigen::Vector3d& seed, LegWorkspace& ws, const IkSettings& settings) {
  const Eigen::Isometry3d W_body = body_W.inverse();
  // The contact's offset from the foot origin turns with the foot: solve, re-aim with the foot's
  // orientation, solve again from there (the offset is a couple of centimetres at most).
  IkResult ik = leg.SolveFootIk(W_body * FootOriginForContact(leg.model(), contact_W, body_W.linear()), seed, ws, settings);
  if (leg.model().foot_sphere_center.isZero()) return ik;
  for (int pass = 0; pass < 3 && ik.ok(); ++pass) {
    const Eigen::Matrix3d foot_rotation_W = body_W.linear() * leg.FootPose(ik.q, ws).linear();
    ik = leg.SolveFootIk(W_body * FootOriginForContact(leg.model(), contact_W, foot_rotation_W), ik.q, ws, settings);
  }
  return ik;
}

StanceResult CheckStance(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                         const StairCollisionModel& stairs, const BodyPose& body,
                         const std::array<Eigen::Vector3d, 4>& contacts_W, RobotWorkspace& ws,
                         const StanceSettings& settings) {
  if (kinematics.leg_count() != 4) throw std::invalid_argument("CheckStance: the robot must have 4 legs");
  for (int l = 0; l < 4; ++l) {
    if (!contacts_W[static_cast<std::size_t>(l)].allFinite()) {
      throw std::invalid_argument("CheckStance: contacts_W[" + std::to_string(l) + "] is not finite");
    }
  }
  const Eigen::Isometry3d body_W = body.ToIsometry();
  StanceResult result;
  result.min_clearance = std::numeric_limits<double>::infinity();
  bool out_of_reach = false, limits = false;
  for (int l = 0; l < 4; ++l) {
    const LegKinematics& leg = kinematics.leg(l);
    LegStance& stance = result.legs[static_cast<std::size_t>(l)];
    const Eigen::Vector3d& contact = contacts_W[static_cast<std::size_t>(l)];
    stance.ik = SolveContactIk(leg, contact, body_W, leg.nominal(), ws.leg(l), settings.ik);
    out_of_reach = out_of_reach || stance.ik.status == IkStatus::kOutOfReach;
    limits = limits || stance.ik.status == IkStatus::kJointLimits;
    if (settings.stop_at_first_failure && (out_of_reach || limits)) {
      result.status = out_of_reach ? StanceStatus::kOutOfReach : StanceStatus::kJointLimits;
      return result;
    }
    stance.stairs = LegStairClearance(kinematics, robot, stairs, l, stance.ik.q, body, ws, settings.clearance);
    if (stance.stairs.distance < result.min_clearance) {
      result.min_clearance = stance.stairs.distance;
      result.worst_leg = l;
    }
    if (settings.stop_at_first_failure && !(stance.stairs.distance > settings.min_clearance)) {
      result.status = StanceStatus::kCollision;
      return result;
    }
  }
  result.body = BodyStairClearance(robot, stairs, body, settings.clearance);
  bool collision = !(result.min_clearance > settings.min_clearance) || !(result.body.distance > settings.min_clearance);
  const double prune = settings.clearance.prune_above;
  const auto pair = [&](int a, int b, Clearance& out) {
    out = LegLegClearance(kinematics, robot, a, result.legs[static_cast<std::size_t>(a)].ik.q, b,
                          result.legs[static_cast<std::size_t>(b)].ik.q, ws, prune);
    collision = collision || !(out.distance > settings.min_clearance);
  };
  if (settings.check_contralateral) {
    pair(0, 1, result.front_pair);
    pair(2, 3, result.hind_pair);
  }
  if (settings.check_ipsilateral) {
    pair(0, 2, result.left_pair);
    pair(1, 3, result.right_pair);
  }
  result.status = out_of_reach ? StanceStatus::kOutOfReach
                  : limits     ? StanceStatus::kJointLimits
                  : collision  ? StanceStatus::kCollision
                               : StanceStatus::kOk;
  return result;
}

StanceChecker::StanceChecker(const RobotModel& robot, const Staircase& stairs, const StanceSettings& settings)
    : StanceChecker(RobotKinematics(robot), stairs, settings) {}

StanceChecker::StanceChecker(const RobotKinematics& kinematics, const Staircase& stairs, const StanceSettings& settings)
    : kinematics_(kinematics), collision_(kinematics_), stairs_(stairs), settings_(settings), ws_(kinematics_) {
  settings_.Validate();
  verdict_settings_ = settings_;
  verdict_settings_.stop_at_first_failure = true;
  // Only "clear of the margin or not" matters there: pairs surely beyond it go unmeasured.
  verdict_settings_.clearance.prune_above = settings_.min_clearance + 1e-6;
}

StanceResult StanceChecker::Check(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W) {
  return CheckStance(kinematics_, collision_, stairs_, body, contacts_W, ws_, settings_);
}

double JudgePruneBound(double smallest, double margin) {
  constexpr double kSlack = 1e-6;  // [m]
  return std::max(smallest, margin) + kSlack;
}

StanceResult StanceChecker::Check(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W, double prune_above) {
  StanceSettings pruned = settings_;
  pruned.clearance.prune_above = std::min(pruned.clearance.prune_above, prune_above);
  return CheckStance(kinematics_, collision_, stairs_, body, contacts_W, ws_, pruned);
}

Interval1 StanceChecker::FeasibleBodyHeights(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W,
                                             double z_lo, double z_hi, double step, double tolerance) {
  if (!(step > 0.0) || !(tolerance > 0.0) || !(z_hi >= z_lo) || !std::isfinite(z_lo) || !std::isfinite(z_hi)) {
    throw std::invalid_argument("StanceChecker::FeasibleBodyHeights: need finite z_lo <= z_hi, step > 0, tolerance > 0");
  }
  BodyPose probe = body;
  const auto passes = [&](double z) {
    probe.position_W.z() = z;
    return CheckStance(kinematics_, collision_, stairs_, probe, contacts_W, ws_, verdict_settings_).ok();
  };
  double run_lo = 0.0, best_lo = 0.0, best_hi = -1.0;
  bool in_run = false;
  const int samples = static_cast<int>(std::floor((z_hi - z_lo) / step + 1e-9));
  for (int i = 0; i <= samples; ++i) {
    const double z = z_lo + i * step;
    if (!passes(z)) {
      in_run = false;
      continue;
    }
    if (!in_run) run_lo = z;
    in_run = true;
    if (z - run_lo > best_hi - best_lo) {
      best_lo = run_lo;
      best_hi = z;
    }
  }
  Interval1 result;
  if (best_hi < best_lo) return result;
  double in = best_lo, out = best_lo - step;
  while (in - out > tolerance && out >= z_lo - step) {
    const double mid = 0.5 * (in + out);
    (passes(mid) ? in : out) = mid;
  }
  result.lo = in;
  in = best_hi;
  out = best_hi + step;
  while (out - in > tolerance) {
    const double mid = 0.5 * (in + out);
    (passes(mid) ? in : out) = mid;
  }
  result.hi = in;
  return result;
}

}  // namespace stairplan
