// BodyPlanner's stance rows: each stance leg's joint limits and extension, linearised at the
// trust region's centre through the leg's KDL Jacobian (stance_leg_rows.h), and its clearance to
// the stairs (FCL's closest points, moved with the body and the joints), as rows of the QP.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "stairplan/collision/clearance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/planning/body/body_planner.h"
#include "stairplan/planning/body/stance_leg_rows.h"

namespace stairplan {
namespace {

// A leg farther than this from the stairs gets no clearance row this cycle: within the trust
// region its links move far less [m].
constexpr double kClearanceRange = 0.05;
// Clearance the rows keep beyond clearance_margin: the validator asks 5 mm of every leg link,
// and a millimetre covers the linearisation between cycles [m].
constexpr double kClearanceInset = 0.006;
// A swing leg's links sweep past the stairs between samples as its foot moves: they keep what its
// foot moves over half a knot, up to this much more (a foot near a nosing moves about a
// centimetre per knot) [m]. A foot slowing to touch down asks less, one on its foothold no more
// than a stance leg.
constexpr double kSwingClearanceInset = 0.006;
// How far a swing foot keeps from the cylinder about its leg's first joint axis (the leg plane's
// offset from it) [m]. Near that cylinder the leg is near its singularity: the abduction turns
// by about 1 / sqrt(d^2 - offset^2) radians per metre the foot moves at distance d from the axis,
// and IK from the nominal angles, the judges', lands on either branch. A swing foot crossing
// there between two knots put a leg past its abduction limit at an instant where both knots
// kept it (a hind foot when the body pitches down a flight); a stance foot keeps the reach
// margin.
constexpr double kSwingAxisMargin = 0.03;
// Step of the finite differences of the closest point's motion [m or rad].
constexpr double kPointStep = 1e-5;
// A clearance the body moves less than this per unit of its own motion gets no row: a link
// point near the foot barely moves with the body (a swing foot follows its trajectory whatever
// the body does, a stance shank pivots about its foot). Normalised, such a row would ask the
// body to move the clearance's deficit divided by this gradient (3 mm at 0.01: 0.3 m), which
// only the knot's relaxation can pay, and that relaxation frees every row of the knot, the
// support rows with it. Such a clearance is the footholds' and the swing trajectory's to keep.
constexpr double kMinClearanceGradient = 0.1;

// The leg on the same side at the other end of the body (legs in LF, RF, LH, RH order).
int SameSideLeg(int l) { return l ^ 2; }

// `at` moved by `step` along body variable v (z, pitch, along, sideways of the heading).
BodyPose Moved(const BodyPose& at, int v, double step) {
  BodyPose moved = at;
  const double c = std::cos(at.yaw), s = std::sin(at.yaw);
  if (v == kBodyZ) moved.position_W.z() += step;
  if (v == kBodyPitch) moved.pitch += step;
  if (v == kBodyAlong) moved.position_W += step * Eigen::Vector3d(c, s, 0.0);
  if (v == kBodySideways) moved.position_W += step * Eigen::Vector3d(-s, c, 0.0);
  return moved;
}

}  // namespace

double BodyPlanner::StandingHeight(const BodyState& start) const {
  // Knot 0 is the state, which no row can move: the robot must stand in a posture its legs hold.
  // The nominal hip height can put a leading knee against the first riser (facing backward the
  // hind knees point at it, and a long head can overhang the first nosing), so the start takes
  // the nearest height, in centimetre steps, at which the body and every leg are as clear of the
  // stairs as the clearance rows keep them and every leg reaches its foot within its limits;
  // none: the nominal one.
  constexpr double kStep = 0.01;
  constexpr int kSteps = 15;
  BodyPose pose;
  pose.position_W = Eigen::Vector3d(start.x, start.y, start.z);
  pose.pitch = start.pitch;
  pose.yaw = start.yaw;
  const double keep = settings_.clearance_margin + kClearanceInset;
  for (int i = 0; i <= 2 * kSteps; ++i) {
    pose.position_W.z() = start.z + (i % 2 == 1 ? 1.0 : -1.0) * ((i + 1) / 2) * kStep;
    bool stands = BodyStairClearance(robot_->collision_model(), robot_->stair_model(), pose, {}).distance >= keep;
    for (int l = 0; l < kBodyLegs && stands; ++l) {
      stands = robot_->CheckLeg(l, schedule_.Phase(l, 0.0).foot_W, pose).ok(keep);
    }
    if (stands) return pose.position_W.z();
  }
  return start.z;
}

Eigen::Vector3d BodyPlanner::FootAt(int l, double t) const { return schedule_.SwingFoot(l, schedule_.Phase(l, t)); }

std::array<Eigen::Vector3d, 2> BodyPlanner::FootBends(int l, double t) const {
  const double dt = settings_.knot_dt;
  const Eigen::Vector3d here = FootAt(l, t);
  return {FootAt(l, t - 0.5 * dt) - 0.5 * (FootAt(l, t - dt) + here),
          FootAt(l, t + 0.5 * dt) - 0.5 * (here + FootAt(l, t + dt))};
}

static_assert(BodyQp::kStanceRows == StanceLegRows::kRows, "the QP holds every row a stance leg has");

void BodyPlanner::StanceRows(int k, double t, const BodyPose& at, const Eigen::Vector4d& v0) {
  BodyQp& qp = *qp_;
  if (!qp.has_stance_rows()) return;
  StanceLegMargins margins{settings_.joint_margin, settings_.reach_margin};
  const Eigen::Matrix3d body_rotation = at.ToIsometry().linear();
  // Knot k + 1 is not linearised yet: the previous plan's interval before the knot tells how fast
  // its links sweep.
  const Eigen::Vector4d motion = k > 0 ? HalfKnotMotion(k - 1, anchors_.col(k - 1), anchors_.col(k)) : Eigen::Vector4d::Zero();
  std::array<StanceLegRows, kBodyLegs> legs;
  for (int l = 0; l < kBodyLegs; ++l) {
    const int first = BodyQp::StanceRow(k, l, 0);
    for (int j = 0; j < BodyQp::kStanceRows; ++j) {
      qp.stance.lo[first + j] = -optim::kInf;
      qp.stance.hi[first + j] = optim::kInf;
      qp.stance.sigma[first + j] = 0.0;
    }
    qp.clearance.lo[BodyQp::ClearanceRow(k, l)] = -optim::kInf;
    qp.clearance.sigma[BodyQp::ClearanceRow(k, l)] = 0.0;
    if (k == 0) continue;  // knot 0 is the measured state
    const LegPhase& phase = phases_[static_cast<std::size_t>(k * kBodyLegs + l)];
    Eigen::Vector3d& q = stance_q_[static_cast<std::size_t>(k * kBodyLegs + l)];
    margins.foot_bends_W = FootBends(l, t);
    legs[static_cast<std::size_t>(l)] = LinearizeLeg(l, phase, at, body_rotation, q, margins);
    const StanceLegRows& rows = legs[static_cast<std::size_t>(l)];
    q = rows.q;
    for (int j = 0; j < BodyQp::kStanceRows; ++j) {
      const std::size_t js = static_cast<std::size_t>(j);
      const double lo = rows.lo[js], hi = rows.hi[js];
      if (!(std::isfinite(lo) && std::isfinite(hi))) continue;  // a row without coefficients
      const double at_v0 = rows.a[js].dot(v0);
      qp.stance.a.row(first + j) = rows.a[js].transpose();
      qp.stance.lo[first + j] = lo + at_v0;
      qp.stance.hi[first + j] = hi + at_v0;
      qp.stance.sigma[first + j] = lo > 0.0 ? lo : hi < 0.0 ? hi : 0.0;  // what the centre breaks
    }
  }
  for (int l = 0; k > 0 && l < kBodyLegs; ++l) {
    const int n = SameSideLeg(l);
    const bool swing = !phases_[static_cast<std::size_t>(k * kBodyLegs + l)].stance;
    const bool n_stands = phases_[static_cast<std::size_t>(k * kBodyLegs + n)].stance;
    ClearanceRow(qp.clearance, k, l, t, at, v0, motion, legs[static_cast<std::size_t>(l)], swing,
                 swing && n_stands ? &legs[static_cast<std::size_t>(n)] : nullptr);
  }
  BodyClearanceRow(qp.clearance, k, at, v0, motion);
}

Eigen::Vector4d BodyPlanner::HalfKnotMotion(int k0, const Eigen::Vector4d& v0, const Eigen::Vector4d& v1) const {
  // The neutral stance carries the body along with it: its advance is part of the motion.
  const double heading = schedule_.heading();
  Eigen::Vector4d motion = v1 - v0;
  motion[kBodyAlong] += heading * (neutral_x_[k0 + 1] - neutral_x_[k0]);
  motion[kBodySideways] += heading * (neutral_y_[k0 + 1] - neutral_y_[k0]);
  return 0.5 * motion;
}

StanceLegRows BodyPlanner::LinearizeLeg(int l, const LegPhase& phase, const BodyPose& at,
                                        const Eigen::Matrix3d& body_rotation, const Eigen::Vector3d& seed,
                                        const StanceLegMargins& margins) {
  // A swing leg's foot is where its swing trajectory has it: its joints and links answer to the
  // body's motion as a stance leg's do.
  const Eigen::Vector3d contact = phase.stance ? phase.foot_W : schedule_.SwingFoot(l, phase);
  const LegKinematics& kin = robot_->kinematics().leg(l);
  LegWorkspace& ws = stance_ws_->leg(l);
  // The foot's sphere rests on the contact; its offset from the foot origin turns with the foot.
  const Eigen::Matrix3d foot_rotation = body_rotation * kin.FootPose(seed, ws).linear();
  const Eigen::Vector3d origin = FootOriginForContact(kin.model(), contact, foot_rotation);
  StanceLegMargins with = margins;
  if (!phase.stance) with.axis = kSwingAxisMargin;
  return LinearizeStanceLeg(kin, ws, origin, at, seed, with);
}

void BodyPlanner::PassingRows(double now) {
  BodyQp& qp = *qp_;
  if (!qp.has_stance_rows()) return;
  const int n = settings_.knots;
  qp.passing.lo.setConstant(-optim::kInf);
  qp.passing.sigma.setZero();
  const StanceLegMargins margins{settings_.joint_margin, settings_.reach_margin};
  const auto near = [&](int k, int l) { return std::isfinite(qp.clearance.lo[BodyQp::ClearanceRow(k, l)]); };
  // From knot 0, the state: the interval the robot executes next.
  for (int k = 0; k + 1 < n; ++k) {
    const double t = now + (k + 0.5) * settings_.knot_dt;
    const Eigen::Vector4d v0 = 0.5 * (centres_.col(k) + centres_.col(k + 1));
    const BodyPose at =
        CentrePose(Eigen::Vector2d(0.5 * (neutral_x_[k] + neutral_x_[k + 1]), 0.5 * (neutral_y_[k] + neutral_y_[k + 1])), v0);
    unsigned parts = 0;  // bit l: leg l (the body: kBodyLegs) has a clearance row at either knot
    for (int part = 0; part <= kBodyLegs; ++part) parts |= near(k, part) || near(k + 1, part) ? 1u << part : 0u;
    const double start = now + k * settings_.knot_dt;
    if (parts != 0 && !(row_cache_ != nullptr && row_cache_->RestorePassing(start, v0, parts, k, qp))) {
      const Eigen::Matrix3d body_rotation = at.ToIsometry().linear();
      const Eigen::Vector4d motion = HalfKnotMotion(k, anchors_.col(k), anchors_.col(k + 1));
      // Each leg linearised at most once per interval: a swing leg's row may need its neighbour's.
      std::array<std::optional<StanceLegRows>, kBodyLegs> linearised;
      const auto rows_of = [&](int leg, const LegPhase& phase) -> const StanceLegRows& {
        std::optional<StanceLegRows>& rows = linearised[static_cast<std::size_t>(leg)];
        if (!rows) rows = LinearizeLeg(leg, phase, at, body_rotation, stance_q_[static_cast<std::size_t>(k * kBodyLegs + leg)], margins);
        return *rows;
      };
      for (int l = 0; l < kBodyLegs; ++l) {
        if ((parts & (1u << l)) == 0) continue;
        const LegPhase phase = schedule_.Phase(l, t);
        // A swing leg passes its standing same-side neighbour too.
        const int mate = SameSideLeg(l);
        const LegPhase mate_phase = schedule_.Phase(mate, t);
        const StanceLegRows* mate_rows = !phase.stance && mate_phase.stance ? &rows_of(mate, mate_phase) : nullptr;
        ClearanceRow(qp.passing, k, l, t, at, v0, motion, rows_of(l, phase), !phase.stance, mate_rows);
      }
      if ((parts & (1u << kBodyLegs)) != 0) BodyClearanceRow(qp.passing, k, at, v0, motion);
      if (row_cache_ != nullptr) row_cache_->StorePassing(start, v0, parts, k, qp);
    }
    // With knot k's relaxation at 1 the previous plan meets the rows, as every knot row's.
    qp.passing.RelaxAt(BodyQp::ClearanceRow(k, 0), BodyQp::kClearanceRows, 0.5 * (anchors_.col(k) + anchors_.col(k + 1)));
  }
}

void BodyPlanner::BodyClearanceRow(BodyQp::KnotRows& into, int k, const BodyPose& at, const Eigen::Vector4d& v0,
                                   const Eigen::Vector4d& motion) {
  const int row = BodyQp::ClearanceRow(k, kBodyLegs);
  into.lo[row] = -optim::kInf;
  into.sigma[row] = 0.0;
  if (k == 0) return;  // knot 0 is the measured state
  ClearanceOptions options;
  options.prune_above = kClearanceRange;
  const Clearance c = BodyStairClearance(robot_->collision_model(), robot_->stair_model(), at, options);
  if (!(c.distance < kClearanceRange) || c.shape < 0) return;
  // The closest point, fixed on the body, moves with it.
  const Eigen::Vector3d point_B = at.ToIsometry().inverse() * c.point_robot_W;
  Eigen::Matrix<double, 3, 4> moved;
  for (int v = 0; v < 4; ++v) moved.col(v) = Moved(at, v, kPointStep).ToIsometry() * point_B;
  SetClearanceRow(into, row, c, v0, motion, kClearanceInset, moved);
}

void BodyPlanner::ClearanceRow(BodyQp::KnotRows& into, int k, int l, double t, const BodyPose& at, const Eigen::Vector4d& v0,
                               const Eigen::Vector4d& motion, const StanceLegRows& rows, bool swing,
                               const StanceLegRows* neighbour) {
  const RobotKinematics& kinematics = robot_->kinematics();
  ClearanceOptions options;
  options.prune_above = kClearanceRange;
  // A stance leg whose IK could not put the foot on its contact has its foot where the IK gave
  // up, often inside the tread: that miss is the reach rows' to resolve, and the foot's
  // penetration, which the body barely moves, would only drag the plan along a useless gradient.
  options.skip_foot_contact = swing || !rows.reached;
  const Clearance c =
      LegStairClearance(kinematics, robot_->collision_model(), robot_->stair_model(), l, rows.q, at, *stance_ws_, options);
  // The foot's motion over the half knot about the row's instant.
  const double quarter = 0.25 * settings_.knot_dt;
  const double foot_sweep = swing ? (FootAt(l, t + quarter) - FootAt(l, t - quarter)).norm() : 0.0;
  const double inset = kClearanceInset + std::min(kSwingClearanceInset, foot_sweep);
  const bool stairs_row = c.distance < kClearanceRange && c.shape >= 0 && c.leg == l;
  if (neighbour != nullptr && neighbour->reached &&
      LegPairRow(into, BodyQp::ClearanceRow(k, l), l, rows, SameSideLeg(l), *neighbour, v0, motion, inset,
                 stairs_row ? c.distance : kClearanceRange)) {
    return;
  }
  if (!stairs_row) return;
  // The closest point, fixed on its link, moves with the body and with the joints, which turn
  // to keep the foot on its contact.
  const LegKinematics& kin = kinematics.leg(l);
  LegWorkspace& ws = stance_ws_->leg(l);
  const int segment = robot_->collision_model().leg_shapes(l)[static_cast<std::size_t>(c.shape)].segment;
  const auto point_at = [&](const BodyPose& pose, const Eigen::Vector3d& q) -> Eigen::Isometry3d {
    const Eigen::Isometry3d body_W = pose.ToIsometry();
    return segment < 0 ? body_W : body_W * kin.LinkFrame(q, segment, ws);
  };
  const Eigen::Vector3d point_link = point_at(at, rows.q).inverse() * c.point_robot_W;
  Eigen::Matrix<double, 3, 4> moved;
  for (int v = 0; v < 4; ++v) {
    moved.col(v) = point_at(Moved(at, v, kPointStep), rows.q + kPointStep * rows.dq.col(v)) * point_link;
  }
  SetClearanceRow(into, BodyQp::ClearanceRow(k, l), c, v0, motion, inset, moved);
}

bool BodyPlanner::LegPairRow(BodyQp::KnotRows& into, int row, int l, const StanceLegRows& rows, int n,
                             const StanceLegRows& rows_n, const Eigen::Vector4d& v0, const Eigen::Vector4d& motion,
                             double inset, double than) {
  const RobotKinematics& kinematics = robot_->kinematics();
  const RobotCollisionModel& model = robot_->collision_model();
  const Clearance c = LegLegClearance(kinematics, model, l, rows.q, n, rows_n.q, *stance_ws_, kClearanceRange);
  if (!(c.distance < std::min(than, kClearanceRange)) || c.shape < 0 || c.other < 0) return false;
  // In the base frame each closest point, fixed on its link, moves only as its leg's joints turn
  // to hold the foot while the body moves: the row is their relative motion.
  const auto frame = [&](int leg, int shape, const Eigen::Vector3d& q) -> Eigen::Isometry3d {
    const int segment = model.leg_shapes(leg)[static_cast<std::size_t>(shape)].segment;
    return segment < 0 ? Eigen::Isometry3d::Identity() : kinematics.leg(leg).LinkFrame(q, segment, stance_ws_->leg(leg));
  };
  const Eigen::Vector3d on_l = frame(l, c.shape, rows.q).inverse() * c.point_robot_W;
  const Eigen::Vector3d on_n = frame(n, c.other, rows_n.q).inverse() * c.point_other_W;
  Eigen::Matrix<double, 3, 4> moved;
  for (int v = 0; v < 4; ++v) {
    const Eigen::Vector3d dl = frame(l, c.shape, rows.q + kPointStep * rows.dq.col(v)) * on_l - c.point_robot_W;
    const Eigen::Vector3d dn = frame(n, c.other, rows_n.q + kPointStep * rows_n.dq.col(v)) * on_n - c.point_other_W;
    moved.col(v) = c.point_robot_W + dl - dn;
  }
  SetClearanceRow(into, row, c, v0, motion, inset, moved);
  return std::isfinite(into.lo[row]);
}

void BodyPlanner::SetClearanceRow(BodyQp::KnotRows& into, int row, const Clearance& c, const Eigen::Vector4d& v0,
                                  const Eigen::Vector4d& motion, double inset, const Eigen::Matrix<double, 3, 4>& moved) {
  Eigen::Vector3d normal = c.point_robot_W - c.point_other_W;
  const double length = normal.norm();
  if (!(length > 1e-9)) return;  // touching: no direction to move away in
  normal *= (c.distance < 0.0 ? -1.0 : 1.0) / length;
  Eigen::Vector4d grad;
  for (int v = 0; v < 4; ++v) grad[v] = normal.dot(moved.col(v) - c.point_robot_W) / kPointStep;
  const double norm = grad.norm();
  if (!(norm >= kMinClearanceGradient)) return;
  // The rows sample the clearance every half knot (the knots' and the passing rows), and a link
  // sweeping past a nosing comes nearest between two samples: a point moving straight by 2h
  // between two instants at which a corner is d away passes at least sqrt(d^2 - h^2) from it.
  // The row asks d of hypot(margin, h), so the nearest approach keeps the margin.
  Eigen::Vector3d sweep = Eigen::Vector3d::Zero();
  for (int v = 0; v < 4; ++v) sweep += (moved.col(v) - c.point_robot_W) * (motion[v] / kPointStep);
  const double half_sweep = 0.5 * sweep.norm();
  const double keep = std::hypot(settings_.clearance_margin + inset, half_sweep);
  into.a.row(row) = (grad / norm).transpose();
  const double lo = (keep - c.distance) / norm;
  into.lo[row] = lo + grad.dot(v0) / norm;
  into.sigma[row] = std::max(lo, 0.0);
}

}  // namespace stairplan
