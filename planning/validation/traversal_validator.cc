#include "planning/validation/traversal_validator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "geometry/field_error.h"

namespace stairplan {
namespace {

constexpr double kTouchTolerance = 1e-4;  // a foot sphere this deep in its tread still only touches [m]

bool QuasiStatic(const std::string& gait) { return gait.rfind("crawl", 0) == 0; }

}  // namespace

const char* ToString(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kFootOutsideStepRegion: return "foot_outside_step_region";
    case ViolationKind::kOutOfReach: return "out_of_reach";
    case ViolationKind::kJointLimits: return "joint_limits";
    case ViolationKind::kStairCollision: return "stair_collision";
    case ViolationKind::kLegCollision: return "leg_collision";
    case ViolationKind::kBodyCollision: return "body_collision";
    case ViolationKind::kStability: return "stability";
    case ViolationKind::kBodyAcceleration: return "body_acceleration";
  }
  return "unknown";
}

void ValidationSettings::Validate() const {
  RequireInRange("time_step", time_step, 1e-4, 1.0);
  RequireInRange("min_clearance", min_clearance, -1.0, 1.0);
  RequireInRange("min_stability_margin", min_stability_margin, -1.0, 1.0);
  RequireInRange("max_body_acceleration", max_body_acceleration, 0.0, 1e4);
  if (max_violations < 1) throw FieldError("max_violations", "must be at least 1");
  swing.Validate();
  ik.Validate();
}

TraversalValidator::TraversalValidator(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                                       const ValidationSettings& settings)
    : stairs_(stairs), map_(map), settings_(settings) {
  settings_.Validate();
  StanceSettings stance;
  stance.ik = settings_.ik;
  stance.min_clearance = settings_.min_clearance;
  checker_ = std::make_unique<StanceChecker>(robot, stairs, stance);
  com_ = std::make_unique<ComModel>(checker_->kinematics());
}

ValidationReport TraversalValidator::Validate(const Plan& plan) {
  ValidationReport report;
  report.min_clearance_m = std::numeric_limits<double>::infinity();
  report.min_stability_margin_m = std::numeric_limits<double>::infinity();
  CheckTouchdowns(plan, report);
  if (QuasiStatic(plan.gait)) CheckBodyAcceleration(plan, report);
  std::set<double> times;
  for (double t = 0.0; t < plan.duration(); t += settings_.time_step) times.insert(t);
  times.insert(plan.duration());
  for (const Footstep& f : plan.footsteps) {
    times.insert(f.t_liftoff);
    times.insert(f.t_touchdown);
  }
  for (double t : times) CheckInstant(plan, t, report);
  std::stable_sort(report.violations.begin(), report.violations.end(),
                   [](const Violation& a, const Violation& b) { return a.t < b.t; });
  if (static_cast<int>(report.violations.size()) > settings_.max_violations) {
    report.violations.resize(static_cast<std::size_t>(settings_.max_violations));
  }
  report.samples = static_cast<int>(times.size());
  report.ok = report.violations.empty() && plan.status == PlanStatus::kOk;
  if (!std::isfinite(report.min_stability_margin_m)) report.min_stability_margin_m = 0.0;
  return report;
}

void TraversalValidator::CheckTouchdowns(const Plan& plan, ValidationReport& report) const {
  for (const Footstep& f : plan.footsteps) {
    const int stair = map_.StairAt(f.position_W.head<2>());
    const bool on_height = stair >= 0 && std::abs(map_.stair(stair).z - f.position_W.z()) < 1e-6;
    if (on_height && map_.InStepRegion(stair, f.position_W.head<2>(), 1e-6)) continue;
    double distance = 0.0;
    map_.NearestStepRegion(f.position_W.head<2>(), &distance);
    report.violations.push_back({f.t_touchdown, f.leg, ViolationKind::kFootOutsideStepRegion, distance,
                                 stair < 0 ? "off the stairs" : "stair " + std::to_string(stair)});
  }
}

// The body's acceleration between consecutive samples, per axis; the first sample beyond the
// bound is reported (once: a jump shows on the samples either side of it).
void TraversalValidator::CheckBodyAcceleration(const Plan& plan, ValidationReport& report) const {
  const std::vector<BodyState>& body = plan.body;
  for (std::size_t i = 1; i + 1 < body.size(); ++i) {
    const Eigen::Vector3d a = BodyAccelerationAt(body, i);
    Eigen::Index axis = 0;
    const double peak = a.cwiseAbs().maxCoeff(&axis);
    if (peak <= settings_.max_body_acceleration) continue;
    report.violations.push_back({body[i].t, "body", ViolationKind::kBodyAcceleration, peak,
                                 std::string("along ") + "xyz"[axis]});
    return;
  }
}

void TraversalValidator::CheckInstant(const Plan& plan, double t, ValidationReport& report) {
  const RobotKinematics& kinematics = checker_->kinematics();
  const BodyPose body = BodyPoseAt(plan.body, t);
  std::vector<bool> down;
  const std::vector<Eigen::Vector3d> feet =
      FeetAlongSwings(plan.legs, plan.initial_feet_W, plan.footsteps, t, stairs_, settings_.swing, &down);
  std::array<Eigen::Vector3d, 4> contacts;
  std::array<bool, 4> stance{true, true, true, true};
  for (std::size_t i = 0; i < plan.legs.size() && i < 4; ++i) {
    const auto l = static_cast<std::size_t>(kinematics.LegIndex(plan.legs[i]));
    contacts[l] = feet[i];
    stance[l] = down[i];
  }
  const StanceResult r = checker_->Check(body, contacts);
  // One entry per leg and kind: the first time it happens.
  std::set<std::pair<std::string, ViolationKind>> seen;
  for (const Violation& v : report.violations) seen.insert({v.leg, v.kind});
  const auto add = [&](const std::string& leg, ViolationKind kind, double value, const std::string& detail) {
    if (seen.insert({leg, kind}).second) report.violations.push_back({t, leg, kind, value, detail});
  };
  for (int l = 0; l < 4; ++l) {
    const LegStance& leg = r.legs[static_cast<std::size_t>(l)];
    const std::string& name = kinematics.leg(l).name();
    if (leg.ik.status == IkStatus::kOutOfReach) add(name, ViolationKind::kOutOfReach, leg.ik.error, "");
    if (leg.ik.status == IkStatus::kJointLimits) add(name, ViolationKind::kJointLimits, leg.ik.error, "");
    const auto& shapes = checker_->collision_model().leg_shapes(l);
    const CollisionShape* shape = leg.stairs.shape >= 0 ? &shapes.at(static_cast<std::size_t>(leg.stairs.shape)) : nullptr;
    // A foot lifting off or touching down grazes its tread by design: only penetration counts.
    const bool foot_on_tread = shape != nullptr && shape->foot_contact && leg.stairs.part == StairPart::kTread;
    if (foot_on_tread && leg.stairs.distance > -kTouchTolerance) continue;
    report.min_clearance_m = std::min(report.min_clearance_m, leg.stairs.distance);
    if (!(leg.stairs.distance > settings_.min_clearance)) {
      add(name, ViolationKind::kStairCollision, leg.stairs.distance,
          (shape != nullptr ? shape->link : std::string("?")) + " against " + ToString(leg.stairs.part));
    }
  }
  for (const Clearance* pair : {&r.front_pair, &r.hind_pair}) {
    report.min_clearance_m = std::min(report.min_clearance_m, pair->distance);
    if (!(pair->distance > settings_.min_clearance)) {
      add(pair == &r.front_pair ? "LF/RF" : "LH/RH", ViolationKind::kLegCollision, pair->distance, "");
    }
  }
  const Clearance body_clearance = BodyStairClearance(checker_->collision_model(), checker_->stairs(), body);
  report.min_clearance_m = std::min(report.min_clearance_m, body_clearance.distance);
  if (!(body_clearance.distance > settings_.min_clearance)) {
    add("body", ViolationKind::kBodyCollision, body_clearance.distance, ToString(body_clearance.part));
  }
  const int stance_count = static_cast<int>(std::count(stance.begin(), stance.end(), true));
  if (stance_count >= 3 && (QuasiStatic(plan.gait) || settings_.stability_for_dynamic_gaits)) {
    std::array<Eigen::Vector3d, 4> q;
    for (int l = 0; l < 4; ++l) q[static_cast<std::size_t>(l)] = r.legs[static_cast<std::size_t>(l)].ik.q;
    const Eigen::Vector3d com = com_->Com(body, q, checker_->workspace());
    std::vector<Eigen::Vector2d> support;
    for (int l = 0; l < 4; ++l) {
      if (stance[static_cast<std::size_t>(l)]) support.push_back(contacts[static_cast<std::size_t>(l)].head<2>());
    }
    const double margin = -ConvexHull(support).SignedDistance(com.head<2>());
    report.min_stability_margin_m = std::min(report.min_stability_margin_m, margin);
    if (margin < settings_.min_stability_margin) add("body", ViolationKind::kStability, margin, "");
  }
}

}  // namespace stairplan
