#include "stairplan/planning/body/body_planner.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stairplan/planning/body/kinematic_body_bounds.h"

namespace stairplan {
namespace {

using Clock = std::chrono::steady_clock;

double ElapsedMicros(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

// Warm-up stops when an iteration moves no knot by more than this [m or rad].
constexpr double kWarmupTolerance = 1e-6;
// A knot whose narrowest stance-leg hip-height range is below this gets its shift reference
// moved to widen it [m]; the candidates span [-max_shift, max_shift].
constexpr double kRestoreWidth = 0.03;
constexpr int kRestoreCandidates = 13;
// The next knot may break a bound by this much before the cycle reports it infeasible [m]: a
// touchdown between knots makes the plan's interpolation break the new stance row by a hair,
// which reach_margin covers.
constexpr double kExecutionTolerance = 0.002;
// Per cycle, a plan that breaks a bound must come this far back [m].
constexpr double kPullIn = 0.001;
// Wanted hip heights are kept this far inside a stance leg's valid range [m].
constexpr double kReferenceInset = 0.002;
// A plan counts as breaking a leg's bound only beyond this [m] (solver tolerance).
constexpr double kRowTolerance = 1e-6;
// Instants closer than this are the same knot [s].
constexpr double kTimeEpsilon = 1e-9;

// sin and cos of one pitch, for the hip offsets of all four legs at it.
struct PitchTurn {
  explicit PitchTurn(double pitch) : s(std::sin(pitch)), c(std::cos(pitch)) {}
  double s, c;
};

// The hip's offset from the body origin, vertical and along the heading (as HipDz, HipDx).
double HipDzAt(const Eigen::Vector3d& hip_B, const PitchTurn& turn) { return -turn.s * hip_B.x() + turn.c * hip_B.z(); }
double HipDxAt(const Eigen::Vector3d& hip_B, const PitchTurn& turn) { return turn.c * hip_B.x() + turn.s * hip_B.z(); }

void CheckFinite(double value, const char* what) {
  if (!std::isfinite(value)) throw std::invalid_argument(std::string("BodyPlanner::Update: ") + what + " is not finite");
}

}  // namespace

BodyPlanner::BodyPlanner(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                         const Plan& footsteps, const BodyPlannerSettings& settings)
    : BodyPlanner(RobotKinematics(robot), stairs, map, footsteps, settings) {}

BodyPlanner::BodyPlanner(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
                         const Plan& footsteps, const BodyPlannerSettings& settings)
    : settings_(settings), schedule_(kinematics.robot(), footsteps, &stairs) {
  settings_.Validate();
  auto bounds = std::make_shared<KinematicBodyBounds>(kinematics, stairs, map.facing(), settings_);
  if (settings_.stance_rows) robot_ = bounds.get();
  const KinematicBodyBounds& kinematic = *bounds;
  bounds_ = std::move(bounds);
  Initialise(kinematics.robot(), stairs, &kinematic.kinematics());
}

BodyPlanner::BodyPlanner(const RobotModel& robot, const Staircase& stairs, const Plan& footsteps,
                         std::shared_ptr<BodyBounds> bounds, const BodyPlannerSettings& settings)
    : settings_(settings), schedule_(robot, footsteps, &stairs), bounds_(std::move(bounds)) {
  settings_.Validate();
  if (!bounds_) throw std::invalid_argument("BodyPlanner: bounds must not be null");
  Initialise(robot, stairs, nullptr);
}

void BodyPlanner::Initialise(const RobotModel& robot, const Staircase& stairs, const RobotKinematics* built) {
  if (robot.legs().size() != static_cast<std::size_t>(kBodyLegs)) {
    throw std::invalid_argument("BodyPlanner: robot '" + robot.name() + "' must have 4 legs");
  }
  // The flight's slope: rise over the horizontal distance between the first and last nosing.
  const auto& edges = stairs.edges();
  double run = stairs.spec().run;
  if (edges.size() >= 2) run = std::abs(edges.back().x_nose - edges.front().x_nose) / static_cast<double>(edges.size() - 1);
  const double rise = stairs.total_rise() / std::max(1, stairs.steps());
  stairs_pitch_ = std::atan2(rise, run);
  const double up = stairs.direction() == TravelDirection::kUp ? 1.0 : -1.0;
  const double nominal_pitch = -schedule_.heading() * up * stairs_pitch_;
  for (int l = 0; l < kBodyLegs; ++l) {
    const LegModel& leg = robot.legs()[static_cast<std::size_t>(l)];
    hips_B_[static_cast<std::size_t>(l)] = leg.hip_B;
    c_[static_cast<std::size_t>(l)] = -std::cos(nominal_pitch) * leg.hip_B.x() - std::sin(nominal_pitch) * leg.hip_B.z();
  }
  hip_height_ = bounds_->NominalHipHeight();
  // With leg rows the ZMP has support rows too, the pendulum as high as the hips (the COM rides
  // within centimetres of them).
  travel_ = schedule_.NeutralBodyXY(schedule_.end_time()).x() >= schedule_.NeutralBodyXY(0.0).x() ? 1.0 : -1.0;
  qp_ = std::make_unique<BodyQp>(settings_, c_, robot_ != nullptr, robot_ != nullptr ? hip_height_ : 0.0,
                                 schedule_.heading() * travel_);
  const int n = settings_.knots;
  if (robot_ != nullptr) {
    const RobotKinematics& kinematics = robot_->kinematics();
    stance_ws_ = std::make_unique<RobotWorkspace>(kinematics);
    com_model_ = std::make_unique<ComModel>(kinematics);
    stance_q_.resize(static_cast<std::size_t>(n * kBodyLegs));
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < kBodyLegs; ++l) stance_q_[static_cast<std::size_t>(k * kBodyLegs + l)] = kinematics.leg(l).nominal();
    }
    // Height has no trust region: its share is of the trust region's shift.
    const double share = settings_.relinearise_share;
    const Eigen::Vector4d max_move(share * settings_.trust_shift, share * settings_.trust_pitch,
                                   share * settings_.trust_shift, share * settings_.trust_lateral);
    if (share > 0.0) row_cache_ = std::make_unique<KnotRowCache>(n, settings_.knot_dt, max_move);
  }
  previous_z_.setZero(n);
  previous_pitch_.setZero(n);
  previous_shift_.setZero(n);
  previous_lateral_.setZero(n);
  phases_.resize(static_cast<std::size_t>((n + 1) * kBodyLegs));
  std::array<Eigen::Vector3d, kBodyLegs> contacts;
  for (int l = 0; l < kBodyLegs; ++l) contacts[static_cast<std::size_t>(l)] = schedule_.Phase(l, 0.0).foot_W;
  com_ = built != nullptr ? CalibrateComEstimate(*built, contacts, StartState())
                          : CalibrateComEstimate(RobotKinematics(robot), contacts, StartState());
  neutral_x_.setZero(n);
  neutral_y_.setZero(n);
  centres_.setZero(4, n);
  anchors_.setZero(4, n);
  com_base_.setZero(2, n);
  support_normal_.setZero(2, BodyQp::kSupportRows * n);
  support_edge_.setZero(BodyQp::kSupportRows * n);
  support_side_.assign(static_cast<std::size_t>(BodyQp::kSupportRows * n), 0);
  leg_lo_.setConstant(n * kBodyLegs, -optim::kInf);
  leg_hi_.setConstant(n * kBodyLegs, optim::kInf);
  output_.knots.resize(static_cast<std::size_t>(n));
  bounds_->SetFootholds(schedule_.footholds());
}

double BodyPlanner::HipDz(int leg, double pitch) const {
  return HipDzAt(hips_B_[static_cast<std::size_t>(leg)], PitchTurn(pitch));
}

double BodyPlanner::HipDx(int leg, double pitch) const {
  return HipDxAt(hips_B_[static_cast<std::size_t>(leg)], PitchTurn(pitch));
}

BodyState BodyPlanner::StartState() const {
  BodyState s;
  const Eigen::Vector2d xy = schedule_.NeutralBodyXY(0.0);
  s.x = xy.x();
  s.y = xy.y();
  s.pitch = std::clamp(schedule_.FeetPitch(0.0), -settings_.max_pitch, settings_.max_pitch);
  s.yaw = schedule_.yaw();
  double z = 0.0;
  for (int l = 0; l < kBodyLegs; ++l) z += (schedule_.Phase(l, 0.0).foot_W.z() + hip_height_ - HipDz(l, s.pitch)) / kBodyLegs;
  s.z = z;
  if (robot_ != nullptr) s.z = StandingHeight(s);
  return s;
}

BodyState BodyPlanner::StartStateAt(const Eigen::Vector2d& standing_xy) const {
  BodyState s = StartState();
  const double h = schedule_.heading();
  s.com_shift = std::clamp(h * (standing_xy.x() - s.x), -settings_.max_shift, settings_.max_shift);
  s.com_shift_y = std::clamp(h * (standing_xy.y() - s.y), -settings_.max_lateral_shift, settings_.max_lateral_shift);
  s.x += h * s.com_shift;
  s.y += h * s.com_shift_y;
  return s;
}

double BodyPlanner::PreviousAt(const Eigen::VectorXd& values, double t) const {
  const double u = (t - previous_t0_) / settings_.knot_dt;
  const int n = static_cast<int>(values.size());
  if (!(u > 0.0)) return values[0];
  // Up to one knot past the end the plan goes on at its last rate, so that a shifted plan keeps
  // its second differences (the acceleration rows) where the previous plan had them; then holds.
  if (u >= n - 1) return values[n - 1] + std::min(u - (n - 1), 1.0) * (values[n - 1] - values[n - 2]);
  const int k = static_cast<int>(u);
  const double a = u - k;
  return (1.0 - a) * values[k] + a * values[k + 1];
}

void BodyPlanner::Linearise(const BodyState& state, const BodyCommand& command, double now) {
  BodyQp& qp = *qp_;
  const int n = settings_.knots;
  const double dt = settings_.knot_dt, pmax = settings_.max_pitch, smax = settings_.max_shift;
  const double ymax = settings_.max_lateral_shift;
  const double heading = schedule_.heading();
  const bool leg_rows = qp.has_stance_rows();
  for (int k = 0; k <= n; ++k) {
    for (int l = 0; l < kBodyLegs; ++l) phases_[static_cast<std::size_t>(k * kBodyLegs + l)] = schedule_.Phase(l, now + k * dt);
  }
  for (int k = 0; k < n; ++k) {
    const double t = now + k * dt;
    const LegPhase* knot_phases = &phases_[static_cast<std::size_t>(k * kBodyLegs)];
    const Eigen::Vector2d xy = schedule_.NeutralBodyXY(t);
    neutral_x_[k] = xy.x();
    neutral_y_[k] = xy.y();
    // The trust region's centre: the previous plan (the state before there is one).
    Eigen::Vector4d v0(state.z, state.pitch, state.com_shift, state.com_shift_y);
    if (k == 0) {
      qp.z_lo[0] = qp.z_hi[0] = state.z;
      qp.pitch_lo[0] = qp.pitch_hi[0] = state.pitch;
      qp.shift_lo[0] = qp.shift_hi[0] = state.com_shift;
      qp.lateral_lo[0] = qp.lateral_hi[0] = state.com_shift_y;
    } else {
      const double y0 = std::clamp(has_previous_ ? PreviousAt(previous_lateral_, t) : state.com_shift_y, -ymax, ymax);
      qp.lateral_lo[k] = std::max(-ymax, y0 - settings_.trust_lateral);
      qp.lateral_hi[k] = std::min(ymax, y0 + settings_.trust_lateral);
      const double p0 = std::clamp(has_previous_ ? PreviousAt(previous_pitch_, t) : state.pitch, -pmax, pmax);
      const double s0 = std::clamp(has_previous_ ? PreviousAt(previous_shift_, t) : state.com_shift, -smax, smax);
      qp.z_lo[k] = -optim::kInf;
      qp.z_hi[k] = optim::kInf;
      qp.pitch_lo[k] = std::max(-pmax, p0 - settings_.trust_pitch);
      qp.pitch_hi[k] = std::min(pmax, p0 + settings_.trust_pitch);
      qp.shift_lo[k] = std::max(-smax, s0 - settings_.trust_shift);
      qp.shift_hi[k] = std::min(smax, s0 + settings_.trust_shift);
      v0 << (has_previous_ ? PreviousAt(previous_z_, t) : state.z), p0, s0, y0;
      if (k == 1) KeepAccelerationAcrossCycles(state, now);
    }
    const double feet_pitch = schedule_.FeetPitch(knot_phases);
    qp.pitch_ref[k] = std::clamp(feet_pitch + command.pitch_offset, -pmax, pmax);
    const double stairness = stairs_pitch_ > 0.0 ? std::clamp(std::abs(feet_pitch) / stairs_pitch_, 0.0, 1.0) : 0.0;
    qp.shift_ref[k] = settings_.stairs_com_shift * stairness;
    qp.lateral_ref[k] = 0.0;
    // The reach rows assume the hips at their nominal sideways offset from the feet; a sideways
    // shift y lengthens the leg by about y^2 / (2 h).
    const double y_far = std::max(std::abs(qp.lateral_lo[k]), std::abs(qp.lateral_hi[k]));
    const double lateral_pad = y_far * y_far / (2.0 * hip_height_);

    const double pl = qp.pitch_lo[k], ph = qp.pitch_hi[k], pm = 0.5 * (pl + ph);
    const PitchTurn turn_l(pl), turn_m(pm), turn_h(ph);
    double narrowest = optim::kInf;  // the stance legs' narrowest hip-height range at this knot
    for (int g = 0; g < qp.groups(); ++g) {
      qp.hip_lo[k * qp.groups() + g] = -optim::kInf;
      qp.hip_hi[k * qp.groups() + g] = optim::kInf;
    }
    for (int l = 0; l < kBodyLegs; ++l) {
      const int row = k * qp.groups() + qp.group_of(l);
      leg_lo_[k * kBodyLegs + l] = -optim::kInf;
      leg_hi_[k * kBodyLegs + l] = optim::kInf;
      const double c = qp.row_coefficient(l);
      const LegPhase& phase = knot_phases[l];
      const Eigen::Vector3d& hip_B = hips_B_[static_cast<std::size_t>(l)];
      qp.height_ref[k * kBodyLegs + l] = phase.foot_W.z() + hip_height_ + command.height_offset - (HipDzAt(hip_B, turn_m) - c * pm);
      if (k == 0) continue;
      // With leg rows each leg's reach, limits and clearance are exact rows of their own, KDL and
      // FCL linearised each cycle: no tabulated hip-height range guides or bounds the plan (its
      // grid is coarse where the rows are exact, and filling it took half the planning time).
      if (leg_rows) continue;
      // The exact hip offsets over the pitch interval: sampled at its ends and middle, padded by
      // the curvature bound (|hip_B| (w/2)^2 / 8 per half).
      const double pad = hip_B.norm() * (ph - pl) * (ph - pl) / 32.0;
      const double e1 = HipDzAt(hip_B, turn_l) - c * pl, e2 = HipDzAt(hip_B, turn_m) - c * pm,
                   e3 = HipDzAt(hip_B, turn_h) - c * ph;
      const double g1 = HipDxAt(hip_B, turn_l), g2 = HipDxAt(hip_B, turn_m), g3 = HipDxAt(hip_B, turn_h);
      const double e_min = std::min({e1, e2, e3}) - pad, e_max = std::max({e1, e2, e3}) + pad;
      const double g_min = std::min({g1, g2, g3}) - pad, g_max = std::max({g1, g2, g3}) + pad;
      // A swinging leg's foot is where its swing trajectory has it: the leg must reach it too
      // (a knot at a liftoff has the foot still on its foothold, in the air a lift brings it
      // nearer the hip), though only stance legs count the foothold's clearance.
      const Eigen::Vector3d contact = schedule_.SwingFoot(l, phase);
      const double base = heading * (xy.x() - contact.x());
      HipBox box;
      box.leg = l;
      box.foothold = phase.foothold;
      box.dx_lo = base + qp.shift_lo[k] + g_min;
      box.dx_hi = base + qp.shift_hi[k] + g_max;
      box.pitch_lo = pl;
      box.pitch_hi = ph;
      const HeightRange range = phase.stance ? bounds_->HipHeight(box) : bounds_->ReachHeight(box);
      const double lo = range.lo + contact.z() - e_min, hi = range.hi + contact.z() - e_max - lateral_pad;
      if (phase.stance) narrowest = std::min(narrowest, range.empty() ? -1.0 : hi - lo);
      // The previous plan (the centre of the trust region) is kept feasible: where it breaks a
      // bound, the bound gives way to it and the row counts as a conflict. So the QP always has
      // a solution, and the cost pulls the plan back inside as the bounds allow.
      const double previous = has_previous_ ? PreviousAt(previous_z_, t) + c * PreviousAt(previous_pitch_, t) : 0.0;
      const bool empty = range.empty() || !(lo <= hi);
      if (empty) {
        leg_lo_[k * kBodyLegs + l] = optim::kInf;  // nothing is valid: always a conflict
        continue;
      }
      leg_lo_[k * kBodyLegs + l] = lo;
      leg_hi_[k * kBodyLegs + l] = hi;
      // A wanted height outside the valid range cannot be had; aiming inside it also pulls a plan
      // that breaks the range (through a row that gave way) back in.
      const double inset = std::min(kReferenceInset, 0.5 * (hi - lo));
      double& ref = qp.height_ref[k * kBodyLegs + l];
      ref = std::clamp(ref, lo + inset, hi - inset);
      double row_lo = std::max(qp.hip_lo[row], lo), row_hi = std::min(qp.hip_hi[row], hi);
      if (has_previous_) {
        // Where the previous plan breaks the bound, the plan must come back by pull_in_ per
        // cycle (so it cannot stay outside while other costs pull it out).
        if (previous < row_lo) row_lo = std::min(row_lo, previous + pull_in_);
        if (previous > row_hi) row_hi = std::max(row_hi, previous - pull_in_);
        if (row_lo > row_hi) row_lo = row_hi = previous;  // two legs of the row disagree: hold
      } else if (row_lo > row_hi) {
        continue;  // two legs of the row disagree and there is no plan to hold: leave it free
      }
      qp.hip_lo[row] = row_lo;
      qp.hip_hi[row] = row_hi;
    }
    if (k > 0 && narrowest < kRestoreWidth) RestoreShift(k, xy.x(), pl, ph, narrowest);
    // A knot new to the horizon is linearised where the previous plan, extrapolated, puts it; where
    // a leg or clearance row breaks there, at the height its feet want instead: on stairs the feet
    // a horizon ahead stand a step higher or lower than the plan's last knot, and rows linearised
    // where no leg reaches point nowhere useful (a stance leg short of its contact, a swing leg
    // deep in a riser), yet the relaxation would let the plan chase them. The relaxation still
    // answers to the previous plan (`anchor`), which the acceleration and progress rows accept,
    // so the QP stays feasible.
    const Eigen::Vector4d anchor = v0;
    const bool new_knot = k > 0 && has_previous_ && t > previous_t0_ + (n - 1) * dt + kTimeEpsilon;
    BodyPose at = CentrePose(xy, v0);
    anchors_.col(k) = anchor;  // the clearance rows read how fast the previous plan moves
    // First the leg rows: the support rows read the legs' joints they solved.
    bool restored = LegRows(k, t, at, v0);
    const bool recentred = new_knot && leg_rows && KnotBreaksRows(k);
    if (recentred) {
      v0[0] = ReferenceHeight(k, v0[1]);
      at = CentrePose(xy, v0);
      restored = LegRows(k, t, at, v0);
    }
    if (row_cache_ != nullptr && k > 0) {
      ++output_.linearised_knots;
      output_.reused_knots += restored ? 1 : 0;
    }
    centres_.col(k) = v0;
    SupportRows(k, t, pm, at, v0, restored);
    if (recentred) {
      qp.stance.RelaxAt(BodyQp::StanceRow(k, 0, 0), kBodyLegs * BodyQp::kStanceRows, anchor);
      qp.clearance.RelaxAt(BodyQp::ClearanceRow(k, 0), BodyQp::kClearanceRows, anchor);
    }
  }
  if (leg_rows) {
    ZmpSupportRows(now);
    ProgressRows();
    PassingRows(now);
  }
}

void BodyPlanner::ZmpSupportRows(double now) {
  BodyQp& qp = *qp_;
  if (qp.zmp_rows().size == 0) return;
  const int n = settings_.knots;
  constexpr int kRows = BodyQp::kSupportRows;
  const double lag = qp.zmp_weight(), dt = settings_.knot_dt;
  // Knot 0's ZMP involves the body executed a cycle ago (a constant; the previous plan's) and
  // knot 1: without its row each cycle could change the executed acceleration at will.
  const double executed_shift = PreviousAt(previous_shift_, now - dt);
  const double executed_lateral = PreviousAt(previous_lateral_, now - dt);
  const auto neutral = [&](int k) -> Eigen::Vector2d {
    if (k < 0) return schedule_.NeutralBodyXY(now - dt);
    if (k >= n) {
      return Eigen::Vector2d(2.0 * neutral_x_[n - 1] - neutral_x_[n - 2], 2.0 * neutral_y_[n - 1] - neutral_y_[n - 2]);
    }
    return Eigen::Vector2d(neutral_x_[k], neutral_y_[k]);
  };
  for (int k = 0; k < n; ++k) {
    // The COM without the weight shifts moves with the neutral stance (it advances during swings
    // only, at constant velocity beyond the horizon): its acceleration moves the ZMP too. The
    // stance's own, not the differences of the exact COMs, whose millimetres of IK noise the
    // pendulum would make decimetres.
    const Eigen::Vector2d zmp_base = com_base_.col(k) - lag * (neutral(k + 1) - 2.0 * neutral(k) + neutral(k - 1));
    const std::array<double, 3> w = qp.ZmpStencil(k);
    for (int r = 0; r < kRows; ++r) {
      const int row = k * kRows + r;
      const int side = support_side_[static_cast<std::size_t>(row)];
      if (side == 0) continue;
      // Knot 0's row holds knot 1 against the body executed a cycle ago, a constant here.
      const double executed =
          k == 0 ? w[0] * (qp.support_cx[row] * executed_shift + qp.support_cy[row] * executed_lateral) : 0.0;
      const double edge = support_edge_[row] - support_normal_.col(row).dot(zmp_base) - executed;
      if (side > 0) {
        qp.zmp_hi[row] = edge;
      } else {
        qp.zmp_lo[row] = edge;
      }
    }
  }
}

BodyPose BodyPlanner::CentrePose(const Eigen::Vector2d& neutral_xy, const Eigen::Vector4d& v0) const {
  const double heading = schedule_.heading();
  BodyPose at;
  at.position_W = Eigen::Vector3d(neutral_xy.x() + heading * v0[2], neutral_xy.y() + heading * v0[3], v0[0]);
  at.pitch = v0[1];
  at.yaw = schedule_.yaw();
  return at;
}

bool BodyPlanner::LegRows(int k, double t, const BodyPose& at, const Eigen::Vector4d& v0) {
  if (row_cache_ == nullptr || k == 0) {
    StanceRows(k, t, at, v0);
    return false;
  }
  Eigen::Vector3d* q = &stance_q_[static_cast<std::size_t>(k * kBodyLegs)];
  const bool restored = row_cache_->Restore(t, v0, k, *qp_, q);
  if (!restored) {
    StanceRows(k, t, at, v0);
    row_cache_->Store(t, v0, k, *qp_, q);
  }
  return restored;
}

bool BodyPlanner::KnotBreaksRows(int k) const {
  const BodyQp& qp = *qp_;
  return (qp.stance.sigma.segment(BodyQp::StanceRow(k, 0, 0), kBodyLegs * BodyQp::kStanceRows).array() != 0.0).any() ||
         (qp.clearance.sigma.segment(BodyQp::ClearanceRow(k, 0), BodyQp::kClearanceRows).array() != 0.0).any();
}

double BodyPlanner::ReferenceHeight(int k, double pitch) const {
  double sum = 0.0;
  for (int l = 0; l < kBodyLegs; ++l) sum += qp_->height_ref[k * kBodyLegs + l] - qp_->row_coefficient(l) * pitch;
  return sum / kBodyLegs;
}

void BodyPlanner::ProgressRows() {
  BodyQp& qp = *qp_;
  for (int k = 0; k + 1 < settings_.knots; ++k) {
    // x = neutral_x + heading shift: its advance along the travel is the neutral body's plus the
    // shift's change times heading * travel (the rows' sign), which may not be negative. Facing
    // against the travel, a shift growing along the heading takes the body back.
    qp.progress_lo[k] = -travel_ * (neutral_x_[k + 1] - neutral_x_[k]);
  }
}

void BodyPlanner::KeepAccelerationAcrossCycles(const BodyState& state, double now) {
  // Knot 0 is the state, the body executed a cycle ago is the previous plan's at now - dt (the
  // state itself before there is a plan): knot 1 may differ from their straight line by the
  // acceleration limit, as the rows within the horizon ask of every other knot. Without this each
  // cycle may pick a new velocity, and the executed body jumps where a row enters the horizon.
  // The same straight line prices knot 1 in the acceleration cost (BodyQp::straight).
  BodyQp& qp = *qp_;
  if (!has_previous_) {  // at rest
    qp.straight = {state.z, state.pitch, state.com_shift, state.com_shift_y};
    return;
  }
  const double dt = settings_.knot_dt, t = now - dt;
  qp.straight = {2.0 * state.z - PreviousAt(previous_z_, t), 2.0 * state.pitch - PreviousAt(previous_pitch_, t),
                 2.0 * state.com_shift - PreviousAt(previous_shift_, t),
                 2.0 * state.com_shift_y - PreviousAt(previous_lateral_, t)};
  const auto window = [&](double straight, double max_accel, double& lo, double& hi) {
    const double reach = max_accel * dt * dt;
    lo = std::max(lo, straight - reach);
    hi = std::min(hi, straight + reach);
    if (lo > hi) lo = hi = std::clamp(straight, hi, lo);  // the trust region or a limit is nearer: its edge
  };
  window(qp.straight[0], settings_.max_height_accel, qp.z_lo[1], qp.z_hi[1]);
  window(qp.straight[1], settings_.max_pitch_accel, qp.pitch_lo[1], qp.pitch_hi[1]);
  window(qp.straight[2], settings_.max_shift_accel, qp.shift_lo[1], qp.shift_hi[1]);
  window(qp.straight[3], settings_.max_lateral_accel, qp.lateral_lo[1], qp.lateral_hi[1]);
}

Eigen::Vector2d BodyPlanner::ComBase(int k, double t, double pitch, const Eigen::Vector2d& feet_sum,
                                     const BodyPose& at, const Eigen::Vector4d& v0, bool restored) {
  const Eigen::Vector2d shift = schedule_.heading() * v0.tail<2>();
  if (com_model_ == nullptr) return com_.At(Eigen::Vector2d(neutral_x_[k], neutral_y_[k]), feet_sum, pitch);
  // Restored leg rows come with the COM computed at their own centre: the affine model below
  // carries it to this one as it carries it over the trust region.
  Eigen::Vector2d kept;
  if (restored && row_cache_->ComBase(t, &kept)) return kept;
  // With the legs' joints at the linearisation point (the leg rows' IK, swing legs on their
  // trajectories) the COM there is exact; the affine estimate's gain carries it over the trust
  // region. The estimate alone misses the legs' own motion by centimetres on heavy-legged robots.
  std::array<Eigen::Vector3d, kBodyLegs> q;
  for (int l = 0; l < kBodyLegs; ++l) q[static_cast<std::size_t>(l)] = stance_q_[static_cast<std::size_t>(k * kBodyLegs + l)];
  const Eigen::Vector2d exact = com_model_->Com(at, q, *stance_ws_).head<2>();
  const Eigen::Vector2d base = exact - com_.gain.cwiseProduct(shift);
  if (!restored && row_cache_ != nullptr) row_cache_->StoreComBase(t, base);
  return base;
}

void BodyPlanner::SupportRows(int k, double t, double pitch, const BodyPose& at, const Eigen::Vector4d& v0,
                              bool restored) {
  BodyQp& qp = *qp_;
  constexpr int kRows = BodyQp::kSupportRows;
  for (int r = 0; r < kRows; ++r) {
    qp.support_lo[k * kRows + r] = -optim::kInf;
    qp.support_hi[k * kRows + r] = optim::kInf;
    qp.zmp_lo[k * kRows + r] = -optim::kInf;
    qp.zmp_hi[k * kRows + r] = optim::kInf;
    support_side_[static_cast<std::size_t>(k * kRows + r)] = 0;
  }
  // Knot 0 is the measured state: only its ZMP has a row, which the next knot moves.
  const bool zmp_only = k == 0;
  if (settings_.stability_margin < 0.0 || (zmp_only && qp.zmp_rows().size == 0)) return;
  // The legs standing on the same foothold at knots k-1, k and k+1: the body moves linearly
  // between knots, so a COM inside their polygon at every knot stays inside the polygon of
  // whatever legs stand in between (a swing starting or ending between two knots included).
  // Knot 0 has no knot before it in the horizon: its own and knot 1's.
  std::array<int, kBodyLegs> foothold{};
  int standing = 0;
  Eigen::Vector2d feet_sum = Eigen::Vector2d::Zero();
  for (int l = 0; l < kBodyLegs; ++l) {
    const LegPhase& now = phases_[static_cast<std::size_t>(k * kBodyLegs + l)];
    const LegPhase& before = phases_[static_cast<std::size_t>((zmp_only ? k : k - 1) * kBodyLegs + l)];
    const LegPhase& after = phases_[static_cast<std::size_t>((k + 1) * kBodyLegs + l)];
    feet_sum += now.foot_W.head<2>();
    const bool stands = now.stance && before.stance && after.stance && before.foothold == now.foothold &&
                        after.foothold == now.foothold;
    foothold[static_cast<std::size_t>(l)] = stands ? now.foothold : -1;
    standing += stands ? 1 : 0;
  }
  const Eigen::Vector2d com_base = ComBase(k, t, pitch, feet_sum, at, v0, restored);
  com_base_.col(k) = com_base;  // every knot's, for the ZMP rows
  if (standing == 2) DiagonalRows(k, foothold);
  if (standing < 3) return;  // no polygon: the gait is not quasi-static here
  const double heading = schedule_.heading();
  const double previous_x = has_previous_ ? PreviousAt(previous_shift_, t) : 0.0;
  const double previous_y = has_previous_ ? PreviousAt(previous_lateral_, t) : 0.0;
  const auto contact = [&](int l) -> Eigen::Vector2d {
    return schedule_.footholds()[static_cast<std::size_t>(foothold[static_cast<std::size_t>(l)])].contact_W.head<2>();
  };
  for (int r = 0; r < kRows; ++r) {
    const auto [i, j] = BodyQp::SupportPair(r);
    if (foothold[static_cast<std::size_t>(i)] < 0 || foothold[static_cast<std::size_t>(j)] < 0) continue;
    const Eigen::Vector2d pi = contact(i), d = contact(j) - pi;
    const double length = d.norm();
    if (!(length > 1e-6)) continue;
    const Eigen::Vector2d normal(d.y() / length, -d.x() / length);
    // An edge of the polygon when every other standing foot is on one side of it.
    int below = 0, above = 0;
    for (int o = 0; o < kBodyLegs; ++o) {
      if (o == i || o == j || foothold[static_cast<std::size_t>(o)] < 0) continue;
      const double side = normal.dot(contact(o) - pi);
      below += side < -1e-9 ? 1 : 0;
      above += side > 1e-9 ? 1 : 0;
    }
    if ((below > 0) == (above > 0)) continue;  // a diagonal of the polygon (or degenerate)
    // COM = com_base + gain .* (heading * (shift, lateral)): the row is normal . COM.
    const int row = k * kRows + r;
    qp.support_cx[row] = normal.x() * com_.gain.x() * heading;
    qp.support_cy[row] = normal.y() * com_.gain.y() * heading;
    const double edge = normal.dot(pi) - normal.dot(com_base);
    if (qp.has_stance_rows()) {
      // Elastic, as the leg rows: a plan the new row excludes (a swing that came into the
      // horizon) keeps the share the relaxation pays for, and the penalty brings it in as fast as
      // the acceleration limits let it. Rows that only give way (below) cannot be pulled in at
      // knots the pinned state and the acceleration limits hold, and then hold the plan still.
      // The ZMP's row too, once every knot's COM is known (ZmpSupportRows).
      support_normal_.col(row) = normal;
      support_edge_[row] = normal.dot(pi);
      support_side_[static_cast<std::size_t>(row)] = below > 0 ? 1 : -1;
      if (zmp_only) continue;
      // The relaxation pays only for what the margin the knot may give cannot: with both at
      // their most the point meets the row, and a point within the margin given relaxes nothing.
      const double value = qp.support_cx[row] * v0[2] + qp.support_cy[row] * v0[3];
      if (below > 0) {
        qp.support_hi[row] = edge - settings_.stability_margin;
        qp.support_sigma[row] = std::min(qp.support_hi[row] + qp.max_give() - value, 0.0);
      } else {
        qp.support_lo[row] = edge + settings_.stability_margin;
        qp.support_sigma[row] = std::max(qp.support_lo[row] - qp.max_give() - value, 0.0);
      }
      continue;
    }
    const double previous = qp.support_cx[row] * previous_x + qp.support_cy[row] * previous_y;
    // A previous plan beyond the row (a swing that just came into the horizon) must come back by
    // half of what the trust region lets the row move per cycle: the row gives way to it, as the
    // hip rows do, so the QP stays feasible. In the retry (pull_in_ = 0) it only holds it.
    const double pull = pull_in_ > 0.0 ? std::max(pull_in_, 0.5 * (std::abs(qp.support_cx[row]) * settings_.trust_shift +
                                                                   std::abs(qp.support_cy[row]) * settings_.trust_lateral))
                                       : 0.0;
    if (below > 0) {
      // The others below: normal . COM <= edge - margin.
      double hi = edge - settings_.stability_margin;
      if (has_previous_ && previous > hi) hi = std::max(hi, previous - pull);
      qp.support_hi[row] = hi;
    } else {
      double lo = edge + settings_.stability_margin;
      if (has_previous_ && previous < lo) lo = std::min(lo, previous + pull);
      qp.support_lo[row] = lo;
    }
  }
}

void BodyPlanner::DiagonalRows(int k, const std::array<int, kBodyLegs>& foothold) {
  BodyQp& qp = *qp_;
  if (qp.zmp_rows().size == 0) return;
  // Two feet carry the body (the trot's diagonal): their forces pass through the line between
  // them, so the pendulum's ZMP must lie on it, between the feet. The COM has no polygon to keep
  // to; the ZMP's four rows bound the line from both sides and its ends, in the knot's rows the
  // absent polygon leaves free, and leave it only by the excursion, as a polygon's do.
  std::array<int, 2> legs{};
  int found = 0;
  for (int l = 0; l < kBodyLegs; ++l) {
    if (foothold[static_cast<std::size_t>(l)] >= 0) legs[static_cast<std::size_t>(found++)] = l;
  }
  const auto contact = [&](int l) -> Eigen::Vector2d {
    return schedule_.footholds()[static_cast<std::size_t>(foothold[static_cast<std::size_t>(l)])].contact_W.head<2>();
  };
  const Eigen::Vector2d a = contact(legs[0]), b = contact(legs[1]);
  const double length = (b - a).norm();
  if (!(length > 1e-6)) return;
  const Eigen::Vector2d along = (b - a) / length, across(along.y(), -along.x());
  const std::array<Eigen::Vector2d, 4> normals = {across, -across, along, -along};
  const std::array<double, 4> bounds = {across.dot(a), -across.dot(a), along.dot(b), -along.dot(a)};
  const double heading = schedule_.heading();
  static_assert(BodyQp::kSupportRows >= 4, "a knot's support rows hold the line's four");
  for (int r = 0; r < 4; ++r) {
    const int row = k * BodyQp::kSupportRows + r;
    const Eigen::Vector2d& normal = normals[static_cast<std::size_t>(r)];
    qp.support_cx[row] = normal.x() * com_.gain.x() * heading;
    qp.support_cy[row] = normal.y() * com_.gain.y() * heading;
    support_normal_.col(row) = normal;
    support_edge_[row] = bounds[static_cast<std::size_t>(r)];
    support_side_[static_cast<std::size_t>(row)] = 1;  // normal . ZMP <= bound
  }
}

void BodyPlanner::RestoreShift(int k, double neutral_x, double pitch_lo, double pitch_hi, double width) {
  // The rows only see the shift through their trust box, so nothing in the QP moves the body
  // fore or aft to widen a leg's range. Here the knot's shift reference moves to the candidate
  // shift that leaves the stance legs the widest ranges; the trust region then walks the plan
  // there over the next cycles, long before the knot is executed.
  const double smax = settings_.max_shift, heading = schedule_.heading();
  const PitchTurn turn(0.5 * (pitch_lo + pitch_hi));
  double best_width = width, best_shift = qp_->shift_ref[k];
  for (int i = 0; i < kRestoreCandidates; ++i) {
    const double s = -smax + 2.0 * smax * i / (kRestoreCandidates - 1);
    double narrowest = optim::kInf;
    for (int l = 0; l < kBodyLegs && narrowest > best_width; ++l) {
      const LegPhase& phase = phases_[static_cast<std::size_t>(k * kBodyLegs + l)];
      if (!phase.stance) continue;
      const Eigen::Vector3d& contact = schedule_.footholds()[static_cast<std::size_t>(phase.foothold)].contact_W;
      HipBox box;
      box.leg = l;
      box.foothold = phase.foothold;
      box.dx_lo = box.dx_hi = heading * (neutral_x - contact.x()) + s + HipDxAt(hips_B_[static_cast<std::size_t>(l)], turn);
      box.pitch_lo = pitch_lo;
      box.pitch_hi = pitch_hi;
      const HeightRange range = bounds_->HipHeight(box);
      narrowest = std::min(narrowest, range.empty() ? -1.0 : range.hi - range.lo);
    }
    if (narrowest > best_width + 1e-4) best_width = narrowest, best_shift = s;
  }
  qp_->shift_ref[k] = best_shift;
}

void BodyPlanner::CountConflicts() {
  output_.conflicts = 0;
  output_.conflict_knot = output_.conflict_leg = -1;
  output_.next_violation = 0.0;
  if (qp_->has_stance_rows()) return;  // the tabulated ranges only guide: nothing to break
  for (int k = 1; k < settings_.knots; ++k) {
    for (int l = 0; l < kBodyLegs; ++l) {
      const double value = previous_z_[k] + qp_->row_coefficient(l) * previous_pitch_[k];
      const double lo = leg_lo_[k * kBodyLegs + l], hi = leg_hi_[k * kBodyLegs + l];
      const double violation = std::max(lo - value, value - hi);
      if (!(violation > kRowTolerance)) continue;
      if (k == 1) output_.next_violation = std::max(output_.next_violation, violation);
      if (output_.conflicts++ == 0) output_.conflict_knot = k, output_.conflict_leg = l;
    }
  }
}

void BodyPlanner::StoreSolution(const optim::SolveResult& result, double now) {
  const int n = settings_.knots;
  previous_t0_ = now;
  previous_z_ = result.x.segment(qp_->z().start, n);
  previous_pitch_ = result.x.segment(qp_->pitch().start, n);
  previous_shift_ = result.x.segment(qp_->shift().start, n);
  previous_lateral_ = qp_->LateralOf(result);
  previous_active_ = result.active_set;
  has_previous_ = true;
}

BodyState BodyPlanner::Interpolate(double t) const {
  BodyState s;
  const Eigen::Vector2d xy = schedule_.NeutralBodyXY(t);
  s.t = t;
  s.com_shift = PreviousAt(previous_shift_, t);
  s.com_shift_y = PreviousAt(previous_lateral_, t);
  s.x = xy.x() + schedule_.heading() * s.com_shift;
  s.y = xy.y() + schedule_.heading() * s.com_shift_y;
  s.z = PreviousAt(previous_z_, t);
  s.pitch = PreviousAt(previous_pitch_, t);
  s.yaw = schedule_.yaw();
  return s;
}

void BodyPlanner::FillOutput(double now) {
  const int n = settings_.knots;
  for (int k = 0; k < n; ++k) {
    const double t = now + k * settings_.knot_dt;
    BodyState& s = output_.knots[static_cast<std::size_t>(k)];
    s.t = t;
    s.com_shift = PreviousAt(previous_shift_, t);
    s.com_shift_y = PreviousAt(previous_lateral_, t);
    s.x = neutral_x_[k] + schedule_.heading() * s.com_shift;
    s.y = neutral_y_[k] + schedule_.heading() * s.com_shift_y;
    s.z = PreviousAt(previous_z_, t);
    s.pitch = PreviousAt(previous_pitch_, t);
    s.yaw = schedule_.yaw();
  }
  for (int l = 0; l < kBodyLegs; ++l) {
    const LegPhase phase = schedule_.Phase(l, now);
    LegTarget& target = output_.feet[static_cast<std::size_t>(l)];
    target.stance = phase.stance;
    target.foot_W = phase.foot_W;
    target.target_W = phase.stance ? phase.foot_W
                                   : schedule_.footholds()[static_cast<std::size_t>(phase.next_foothold)].contact_W;
    target.t_liftoff = phase.t_liftoff;
    target.t_touchdown = phase.t_touchdown;
  }
}

double BodyPlanner::kDefaultPullIn() { return kPullIn; }

const BodyPlannerOutput& BodyPlanner::Update(const BodyState& state, const BodyCommand& command, double now) {
  const Clock::time_point start = Clock::now();
  CheckFinite(now, "now");
  CheckFinite(state.z, "state.z");
  CheckFinite(state.pitch, "state.pitch");
  CheckFinite(state.com_shift, "state.com_shift");
  CheckFinite(state.com_shift_y, "state.com_shift_y");
  CheckFinite(command.height_offset, "command.height_offset");
  CheckFinite(command.pitch_offset, "command.pitch_offset");
  output_.solves = 0;
  output_.iterations = 0;
  output_.linearised_knots = output_.reused_knots = 0;
  output_.timings = {};
  bool solved = false;
  if (!has_previous_) {
    // Warm-up: converge the linearisation at this instant, without a budget, starting from the
    // state held over the horizon (a plan the rows then give way to where they must).
    qp_->ResetWarmStart();
    previous_t0_ = now;
    previous_z_.setConstant(state.z);
    previous_pitch_.setConstant(state.pitch);
    previous_shift_.setConstant(state.com_shift);
    previous_lateral_.setConstant(state.com_shift_y);
    has_previous_ = true;
    for (int i = 0; i < settings_.warmup_solves; ++i) {
      const Clock::time_point t0 = Clock::now();
      Linearise(state, command, now);
      const Clock::time_point t1 = Clock::now();
      output_.timings.bounds_us += std::chrono::duration<double, std::micro>(t1 - t0).count();
      qp_->Solve(optim::kInf, &result_);
      output_.timings.solve_us += ElapsedMicros(t1);
      ++output_.solves;
      output_.iterations += result_.info.iterations;
      solved = result_.solved() && result_.x.allFinite();
      if (!solved && i > 0) {
        // As in the cycle: rows that only hold the last iterate (which satisfies them) where
        // pulling it in is too much at once.
        pull_in_ = 0.0;
        Linearise(state, command, now);
        pull_in_ = kPullIn;
        qp_->Solve(optim::kInf, &result_);
        ++output_.solves;
        solved = result_.solved() && result_.x.allFinite();
      }
      if (!solved) {
        has_previous_ = false;
        break;
      }
      const int n = settings_.knots;
      const double change =
          i > 0 ? std::max({(result_.x.segment(qp_->z().start, n) - previous_z_).lpNorm<Eigen::Infinity>(),
                                    (result_.x.segment(qp_->pitch().start, n) - previous_pitch_).lpNorm<Eigen::Infinity>(),
                                    (result_.x.segment(qp_->shift().start, n) - previous_shift_).lpNorm<Eigen::Infinity>(),
                                    (qp_->LateralOf(result_) - previous_lateral_).lpNorm<Eigen::Infinity>()})
                        : optim::kInf;
      StoreSolution(result_, now);
      if (change < kWarmupTolerance) break;
    }
    solve_estimate_us_ = 0.0;
  } else {
    // The knots of the stored plan, a cycle ago, lie that many knots later than now's.
    const int advanced = static_cast<int>(std::lround((now - previous_t0_) / settings_.knot_dt));
    if (advanced > 0) qp_->ShiftWarmStart(previous_active_, advanced);
    Linearise(state, command, now);
    output_.timings.bounds_us = ElapsedMicros(start);
    const double remaining_us = settings_.cycle_budget_s * 1e6 - output_.timings.bounds_us;
    if (remaining_us > solve_estimate_us_) {
      const Clock::time_point t1 = Clock::now();
      qp_->Solve(remaining_us * 1e-6, &result_);
      const double solve_us = ElapsedMicros(t1);
      output_.timings.solve_us = solve_us;
      solve_estimate_us_ = 0.9 * solve_estimate_us_ + 0.1 * solve_us;
      ++output_.solves;
      output_.iterations = result_.info.iterations;
      solved = result_.solved() && result_.x.allFinite();
      if (!solved && result_.status != optim::SolveStatus::kTimeLimit) {
        // Pulling a plan that breaks a bound back inside may be too much for one cycle (the
        // acceleration limits): try once more with rows that only hold it where it is, which
        // the shifted previous plan satisfies (warm: the solver re-checks a warm Infeasible cold).
        pull_in_ = 0.0;
        Linearise(state, command, now);
        pull_in_ = kPullIn;
        const double left_us = settings_.cycle_budget_s * 1e6 - ElapsedMicros(start);
        if (left_us > 0.0) {
          qp_->Solve(left_us * 1e-6, &result_);
          ++output_.solves;
          solved = result_.solved() && result_.x.allFinite();
        }
      }
      output_.timings.solve_us = ElapsedMicros(t1);
      if (solved) StoreSolution(result_, now);
    } else {
      result_.status = optim::SolveStatus::kTimeLimit;
    }
  }
  output_.solve_status = result_.status;
  output_.relaxation = solved && qp_->relax().size > 0 ? std::clamp(result_.x[qp_->relax().start + 1], 0.0, 1.0) : 0.0;
  if (solved) CountConflicts();
  if (solved) {
    // Conflicts further ahead are the receding horizon's to resolve; the next knot is executed now.
    output_.status = output_.next_violation > kExecutionTolerance ? BodyPlanStatus::kInfeasible : BodyPlanStatus::kOk;
  } else if (has_previous_) {
    output_.status = BodyPlanStatus::kStale;  // the shifted previous plan
  } else {
    output_.status = BodyPlanStatus::kInfeasible;
  }
  if (!has_previous_) {
    // Nothing solved yet: hold the state over the horizon.
    previous_t0_ = now;
    previous_z_.setConstant(state.z);
    previous_pitch_.setConstant(state.pitch);
    previous_shift_.setConstant(state.com_shift);
    previous_lateral_.setConstant(state.com_shift_y);
  }
  FillOutput(now);
  output_.timings.total_us = ElapsedMicros(start);
  return output_;
}

}  // namespace stairplan
