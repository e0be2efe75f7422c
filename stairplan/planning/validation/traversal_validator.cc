#include "stairplan/planning/validation/traversal_validator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/validation/body_rates.h"

namespace stairplan {
namespace {

// A replay instant this close to a liftoff or touchdown is that event: footstep times are sums of
// cadences (8.400000000000002), and a grid instant a rounding error before a touchdown would judge
// the landing foot in the air and the COM, already shifting for the next swing, against the
// triangle of the other three [s].
constexpr double kEventTolerance = 1e-9;

// The instants a plan is replayed at: every liftoff and touchdown, the end, and a grid of
// `time_step` whose instants within kEventTolerance of an event are that event.
std::set<double> ReplayInstants(const Plan& plan, double time_step) {
  std::set<double> events;
  for (const Footstep& f : plan.footsteps) {
    events.insert(f.t_liftoff);
    events.insert(f.t_touchdown);
  }
  std::set<double> times = events;
  times.insert(plan.duration());
  const auto near_event = [&events](double t) {
    const auto after = events.lower_bound(t - kEventTolerance);
    return after != events.end() && *after <= t + kEventTolerance;
  };
  const auto steps = static_cast<long>(std::ceil(plan.duration() / time_step));
  for (long i = 0; i < steps; ++i) {
    const double t = static_cast<double>(i) * time_step;
    if (t < plan.duration() && !near_event(t)) times.insert(t);
  }
  return times;
}

bool QuasiStatic(const std::optional<Gait>& gait) { return gait && IsQuasiStatic(*gait); }

// The dynamic check's mode for a plan walking `gait`: reported becomes judged for a gait whose
// pace needs it (IsJudgedDynamically); off stays off.
DynamicsCheckMode ModeFor(DynamicsCheckMode mode, const std::optional<Gait>& gait) {
  if (mode == DynamicsCheckMode::kReport && gait && IsJudgedDynamically(*gait)) return DynamicsCheckMode::kJudge;
  return mode;
}

// The leg a violation's leg name means, kNone for the body, leg pairs and unknown names.
LegId LegIdOfName(const RobotKinematics& kinematics, const std::string& name) {
  for (int l = 0; l < kinematics.leg_count(); ++l) {
    if (kinematics.leg(l).name() == name) return LegIdFromIndex(l);
  }
  return LegId::kNone;
}

ViolationKind KindOf(WrenchLimit limit) {
  switch (limit) {
    case WrenchLimit::kFrictionCone: return ViolationKind::kFrictionCone;
    case WrenchLimit::kTorqueLimit: return ViolationKind::kTorqueLimit;
    case WrenchLimit::kNone:
    case WrenchLimit::kWrenchUnattainable: return ViolationKind::kWrenchUnattainable;
  }
  return ViolationKind::kWrenchUnattainable;
}

// Every stair surface of a Staircase is a level top (one height per surface): the normal under any
// foot on the stairs is up. Kept as the one place to change when surfaces tilt.
Eigen::Vector3d SurfaceNormalUnder(const Staircase& /*stairs*/, const Eigen::Vector3d& /*foot_W*/) {
  return Eigen::Vector3d::UnitZ();
}

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
    case ViolationKind::kFrictionCone: return "friction_cone";
    case ViolationKind::kTorqueLimit: return "torque_limit";
    case ViolationKind::kWrenchUnattainable: return "wrench_unattainable";
    case ViolationKind::kSupportLineTilt: return "support_line_tilt";
  }
  return "unknown";
}

const char* ToString(CheckFamily family) {
  switch (family) {
    case CheckFamily::kStepRegions: return "step_regions";
    case CheckFamily::kKinematics: return "kinematics";
    case CheckFamily::kCollision: return "collision";
    case CheckFamily::kStability: return "stability";
    case CheckFamily::kBodyAcceleration: return "body_acceleration";
    case CheckFamily::kDynamics: return "dynamics";
  }
  return "unknown";
}

CheckFamily FamilyOf(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kFootOutsideStepRegion: return CheckFamily::kStepRegions;
    case ViolationKind::kOutOfReach:
    case ViolationKind::kJointLimits: return CheckFamily::kKinematics;
    case ViolationKind::kStairCollision:
    case ViolationKind::kLegCollision:
    case ViolationKind::kBodyCollision: return CheckFamily::kCollision;
    case ViolationKind::kStability: return CheckFamily::kStability;
    case ViolationKind::kBodyAcceleration: return CheckFamily::kBodyAcceleration;
    case ViolationKind::kFrictionCone:
    case ViolationKind::kTorqueLimit:
    case ViolationKind::kWrenchUnattainable:
    case ViolationKind::kSupportLineTilt: return CheckFamily::kDynamics;
  }
  return CheckFamily::kDynamics;
}

bool LargerIsWorse(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kStairCollision:
    case ViolationKind::kLegCollision:
    case ViolationKind::kBodyCollision:
    case ViolationKind::kStability: return false;
    default: return true;
  }
}

namespace {

// One entry per leg and kind: the first time it happens, with the worst value since.
void Record(const Violation& v, ValidationReport& report) {
  for (Violation& listed : report.violations) {
    if (listed.leg != v.leg || listed.kind != v.kind) continue;
    if (LargerIsWorse(v.kind) ? v.value > listed.worst : v.value < listed.worst) {
      listed.worst = v.value;
      listed.t_worst = v.t;
    }
    return;
  }
  report.violations.push_back(v);
}

}  // namespace

void ValidationSettings::Validate() const {
  RequireInRange("time_step", time_step, 1e-4, 1.0);
  RequireInRange("min_clearance", min_clearance, -1.0, 1.0);
  RequireInRange("min_stability_margin", min_stability_margin, -1.0, 1.0);
  RequireInRange("max_body_acceleration", max_body_acceleration, 0.0, 1e4);
  if (max_violations < 1) throw FieldError("max_violations", "must be at least 1");
  swing.Validate();
  ik.Validate();
  dynamics.Validate();
}

void ValidationSettings::Set(const std::string& name, double value) {
  if (name == "dynamics") {
    if (!(value == 0.0 || value == 1.0 || value == 2.0)) throw FieldError(name, "must be 0 (off), 1 (report) or 2 (judge)");
    dynamics.mode = static_cast<DynamicsCheckMode>(static_cast<int>(value));
    return;
  }
  if (name == "friction_faces") {
    if (!(value >= 4 && value <= 64 && value == std::floor(value))) throw FieldError(name, "must be a whole number in [4, 64]");
    dynamics.friction_faces = static_cast<int>(value);
    return;
  }
  const std::map<std::string, double*> fields = {
      {"friction", &dynamics.friction}, {"residual_tolerance", &dynamics.residual_tolerance},
      {"time_step", &time_step}, {"min_clearance", &min_clearance}, {"min_stability_margin", &min_stability_margin},
      {"max_body_acceleration", &max_body_acceleration}};
  const auto it = fields.find(name);
  if (it == fields.end()) throw FieldError(name, "is not a validator setting");
  *it->second = value;
}

TraversalValidator::TraversalValidator(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                                       const ValidationSettings& settings)
    : TraversalValidator(RobotKinematics(robot), stairs, map, settings) {}

TraversalValidator::TraversalValidator(const RobotKinematics& kinematics, const Staircase& stairs,
                                       const ConstrainedMap& map, const ValidationSettings& settings)
    : stairs_(stairs), map_(map), settings_(settings) {
  settings_.Validate();
  StanceSettings stance;
  stance.ik = settings_.ik;
  stance.min_clearance = settings_.min_clearance;
  checker_ = std::make_unique<StanceChecker>(kinematics, stairs, stance);
  com_ = std::make_unique<ComModel>(checker_->kinematics());
  wrench_ = std::make_unique<ContactWrenchCheck>(checker_->kinematics(), com_->total_mass(), settings_.dynamics);
}

ValidationReport TraversalValidator::Validate(const Plan& plan) {
  ValidationReport report;
  report.min_clearance_m = std::numeric_limits<double>::infinity();
  report.min_stability_margin_m = std::numeric_limits<double>::infinity();
  dynamics_mode_ = ModeFor(settings_.dynamics.mode, plan.gait);
  report.dynamics.mode = dynamics_mode_;
  report.dynamics.torque_limits_checked = wrench_->torque_limits_checked();
  report.dynamics.body_inertia_known = wrench_->body_inertia_known();
  report.dynamics.friction = settings_.dynamics.friction;
  report.dynamics.tolerance_n = wrench_->tolerance();
  CheckTouchdowns(plan, report);
  line_pair_ = 0;
  if (QuasiStatic(plan.gait)) CheckBodyAcceleration(plan, report);
  const std::set<double> times = ReplayInstants(plan, settings_.time_step);
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
                                 stair < 0 ? "off the stairs" : "stair " + std::to_string(stair),
                                 LegIdOfName(checker_->kinematics(), f.leg), distance, f.t_touchdown});
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
                                 std::string("along ") + "xyz"[axis], LegId::kNone, peak, body[i].t});
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
  // Only clearances below the margin and the smallest of the replay are reported: a shape pair
  // surely farther apart than both needs no measuring, and the reported ones stay exact.
  const double prune = JudgePruneBound(report.min_clearance_m, settings_.min_clearance);
  const StanceResult r = checker_->Check(body, contacts, prune);
  const auto add = [&](const std::string& leg, ViolationKind kind, double value, const std::string& detail) {
    Record({t, leg, kind, value, detail, LegIdOfName(kinematics, leg), value, t}, report);
  };
  for (int l = 0; l < 4; ++l) {
    const LegStance& leg = r.legs[static_cast<std::size_t>(l)];
    const std::string& name = kinematics.leg(l).name();
    if (leg.ik.status == IkStatus::kOutOfReach) add(name, ViolationKind::kOutOfReach, leg.ik.error, "");
    if (leg.ik.status == IkStatus::kJointLimits) add(name, ViolationKind::kJointLimits, leg.ik.error, "");
    if (FootGrazesTread(checker_->collision_model(), l, leg.stairs)) continue;
    const auto& shapes = checker_->collision_model().leg_shapes(l);
    const CollisionShape* shape = leg.stairs.shape >= 0 ? &shapes.at(static_cast<std::size_t>(leg.stairs.shape)) : nullptr;
    report.min_clearance_m = std::min(report.min_clearance_m, leg.stairs.distance);
    if (!(leg.stairs.distance > settings_.min_clearance)) {
      add(name, ViolationKind::kStairCollision, leg.stairs.distance,
          (shape != nullptr ? shape->link : std::string("?")) + " against " + ToString(leg.stairs.part));
    }
  }
  const std::array<std::pair<const char*, const Clearance*>, 4> pairs = {
      {{"LF/RF", &r.front_pair}, {"LH/RH", &r.hind_pair}, {"LF/LH", &r.left_pair}, {"RF/RH", &r.right_pair}}};
  for (const auto& [name, pair] : pairs) {
    report.min_clearance_m = std::min(report.min_clearance_m, pair->distance);
    if (!(pair->distance > settings_.min_clearance)) add(name, ViolationKind::kLegCollision, pair->distance, "");
  }
  ClearanceOptions body_options;
  body_options.prune_above = prune;
  const Clearance body_clearance = BodyStairClearance(checker_->collision_model(), checker_->stairs(), body, body_options);
  report.min_clearance_m = std::min(report.min_clearance_m, body_clearance.distance);
  if (!(body_clearance.distance > settings_.min_clearance)) {
    add("body", ViolationKind::kBodyCollision, body_clearance.distance, ToString(body_clearance.part));
  }
  if (dynamics_mode_ != DynamicsCheckMode::kOff) CheckDynamics(plan, t, r, contacts, stance, report);
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

// The first instant each leg and limit fails is listed (as every other check lists its first
// time); the summary keeps the worst residual and how many instants failed.
void TraversalValidator::CheckDynamics(const Plan& plan, double t, const StanceResult& stance_result,
                                       const std::array<Eigen::Vector3d, 4>& contacts, const std::array<bool, 4>& stance,
                                       ValidationReport& report) {
  instant_.body = BodyPoseAt(plan.body, t);
  instant_.rates = BodyRatesAt(plan.body, t);
  for (std::size_t l = 0; l < 4; ++l) {
    instant_.q[l] = stance_result.legs[l].ik.q;
    instant_.feet_W[l] = contacts[l];
    instant_.normals_W[l] = SurfaceNormalUnder(stairs_, contacts[l]);
    instant_.stance[l] = stance[l];
  }
  instant_.com_W = com_->Com(instant_.body, instant_.q, checker_->workspace());
  const WrenchResult& w = wrench_->Check(instant_, checker_->workspace());
  CheckLineTilt(t, report);
  DynamicsReport& summary = report.dynamics;
  if (w.residual > summary.max_residual_n) {
    summary.max_residual_n = w.residual;
    summary.max_residual_t = t;
  }
  if (w.within_tolerance) return;
  const ViolationKind kind = KindOf(w.limit);
  if (summary.failed_instants++ == 0) {
    summary.first_failure_t = t;
    summary.first_failure_kind = kind;
    summary.first_failure_leg = w.leg;
  }
  if (dynamics_mode_ != DynamicsCheckMode::kJudge) return;
  const std::string leg = w.leg == LegId::kNone ? std::string("body") : std::string(ToString(w.leg));
  std::string detail = "friction " + std::to_string(settings_.dynamics.friction);
  if (!w.solved) detail += ", the QP did not solve";
  Record({t, leg, kind, w.residual, detail, w.leg, w.residual, t}, report);
}

void TraversalValidator::CheckLineTilt(double t, ValidationReport& report) {
  const LineSupport& line = wrench_->line();
  // A new phase (or a gap in the replay) starts from rest: the four-feet phase before it is the
  // executor's to level the body in.
  const bool continues = line.active && line.pair == line_pair_ && t - tilt_t_ <= 2.0 * settings_.time_step + 1e-9;
  if (!continues) tilt_ = tilt_rate_ = 0.0;
  line_pair_ = line.active ? line.pair : 0;
  if (!line.active || !(line.inertia > 0.0)) return;
  if (continues) {
    // The moment the feet cannot give turns the body the other way; the tilt topples it further.
    const double dt = t - tilt_t_;
    tilt_rate_ += dt * (-line.moment + line.stiffness * tilt_) / line.inertia;
    tilt_ += dt * tilt_rate_;
  }
  tilt_t_ = t;
  DynamicsReport& summary = report.dynamics;
  const double tilt = std::abs(tilt_);
  if (tilt > summary.max_line_tilt_rad) {
    summary.max_line_tilt_rad = tilt;
    summary.max_line_tilt_t = t;
  }
  if (tilt <= settings_.dynamics.max_line_tilt || dynamics_mode_ != DynamicsCheckMode::kJudge) return;
  const RobotKinematics& kinematics = checker_->kinematics();
  std::string legs;
  for (int l = 0; l < kinematics.leg_count() && l < 4; ++l) {
    if (line.pair & (1 << l)) legs += (legs.empty() ? "" : "+") + kinematics.leg(l).name();
  }
  char detail[96];
  std::snprintf(detail, sizeof(detail), "tilt %.4f rad about %s's line, tolerance %.4f", tilt, legs.c_str(),
                settings_.dynamics.max_line_tilt);
  Record({t, "body", ViolationKind::kSupportLineTilt, tilt, detail, LegId::kNone, tilt, t}, report);
}

}  // namespace stairplan
