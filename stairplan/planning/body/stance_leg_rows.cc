#include "stairplan/planning/body/stance_leg_rows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace stairplan {
namespace {

// Below this |det J| (relative to the product of its columns' lengths) the leg is near a
// singularity, stretched nearly straight: the joint rows' first-order model is then wrong within
// millimetres (their coefficients grow as 1/det), so only the extension row, which stays smooth
// there, bounds the leg.
constexpr double kSingularDet = 0.02;
// Step of the first joint for the flexion joint's derivative (forward difference) [rad].
constexpr double kTurnStep = 1e-6;

// How far a quantity strays between knots beyond the knots' average, up and down, from its
// departures at the middles of the intervals before and after the knot.
struct Bulge {
  double up = 0.0, down = 0.0;
};
Bulge BulgeOf(double before, double after) {
  return {std::max({0.0, before, after}), std::max({0.0, -before, -after})};
}

// Normalises row r (its coefficients to unit length); an all-zero row is left free. Margins and
// a swing's bulge wider than the joint's or the extension's whole range leave lo above hi: the row
// then asks for the middle of what they leave, the point farthest from both limits.
void SetRow(StanceLegRows* rows, int r, const Eigen::Vector4d& a, double lo, double hi) {
  if (lo > hi) lo = hi = 0.5 * (lo + hi);
  const double norm = a.norm();
  auto& row_a = rows->a[static_cast<std::size_t>(r)];
  if (!(norm > 1e-12)) {
    row_a.setZero();
    rows->lo[static_cast<std::size_t>(r)] = -std::numeric_limits<double>::infinity();
    rows->hi[static_cast<std::size_t>(r)] = std::numeric_limits<double>::infinity();
    return;
  }
  row_a = a / norm;
  rows->lo[static_cast<std::size_t>(r)] = lo / norm;
  rows->hi[static_cast<std::size_t>(r)] = hi / norm;
}

// The flexion and knee joints move the foot in a plane at a fixed offset from the first joint's
// axis (the flexion joint's axis is its normal): no joint angles put the foot nearer that axis
// than the offset. A hind foot passes there when the body pitches down a flight travelling
// backward; at the cylinder's surface the leg is singular and inside it the joint rows have no
// first-order model, so this row, smooth everywhere but on the axis, keeps the foot out.
struct AxisDistance {
  double offset = 0.0;                            // the leg plane's distance from the axis [m]
  double distance = 0.0;                          // the foot's [m]
  Eigen::Vector3d out = Eigen::Vector3d::Zero();  // away from the axis, through the foot
  bool valid = false;                             // a revolute first joint, the foot off its axis
};
AxisDistance AxisDistanceOf(const LegKinematics& kin, LegWorkspace& ws, const Eigen::Vector3d& q,
                            const Eigen::Vector3d& foot_B) {
  AxisDistance a;
  const LegKinematics::JointLine first = kin.JointLineAt(q, 0, ws);
  if (first.prismatic) return a;
  const Eigen::Vector3d normal = kin.JointLineAt(q, 1, ws).axis;
  a.offset = std::abs((kin.FootPosition(q, ws) - first.origin).dot(normal));
  const Eigen::Vector3d lever = foot_B - first.origin;
  const Eigen::Vector3d radial = lever - lever.dot(first.axis) * first.axis;
  a.distance = radial.norm();
  if (!(a.distance > 1e-9)) return a;
  a.out = radial / a.distance;
  a.valid = true;
  return a;
}

// The judges (the stance check, the validator) solve IK from the nominal angles; a seed carried
// from cycle to cycle can slide onto another branch (the knee bent the other way, the abduction
// turned over), where the leg's links, and so its clearance and limits, are not the ones they
// check. True while q is on the nominal's branch: the knee bent the same way, no joint a quarter
// turn or more from it.
bool OnNominalBranch(const Eigen::Vector3d& q, const Eigen::Vector3d& nominal) {
  return q[2] * nominal[2] >= 0.0 && (q - nominal).cwiseAbs().maxCoeff() < 0.5 * M_PI;
}

}  // namespace

StanceLegRows LinearizeStanceLeg(const LegKinematics& kin, LegWorkspace& ws, const Eigen::Vector3d& foot_W,
                                 const BodyPose& pose, const Eigen::Vector3d& seed, const StanceLegMargins& margins) {
  const double cy = std::cos(pose.yaw), sy = std::sin(pose.yaw), cp = std::cos(pose.pitch), sp = std::sin(pose.pitch);
  // The foot relative to the body in the heading frame, then in the base frame (R = Rz Ry).
  const auto to_heading = [&](const Eigen::Vector3d& v_W) {
    return Eigen::Vector3d(cy * v_W.x() + sy * v_W.y(), -sy * v_W.x() + cy * v_W.y(), v_W.z());
  };
  const Eigen::Vector3d rel_H = to_heading(foot_W - pose.position_W);
  Eigen::Matrix3d ry_t;  // Ry(pitch)^T
  ry_t << cp, 0.0, -sp, 0.0, 1.0, 0.0, sp, 0.0, cp;
  Eigen::Matrix3d dry_t;  // d Ry(pitch)^T / d pitch
  dry_t << -sp, 0.0, -cp, 0.0, 0.0, 0.0, cp, 0.0, -sp;
  const Eigen::Vector3d foot_B = ry_t * rel_H;
  const std::array<Eigen::Vector3d, 2> bends_B{ry_t * to_heading(margins.foot_bends_W[0]),
                                               ry_t * to_heading(margins.foot_bends_W[1])};
  // D: d foot_B / d (z, pitch, along, sideways); moving the body moves the foot the other way.
  Eigen::Matrix<double, 3, 4> d;
  d.col(kBodyZ) = -ry_t.col(2);
  d.col(kBodyPitch) = dry_t * rel_H;
  d.col(kBodyAlong) = -ry_t.col(0);
  d.col(kBodySideways) = -ry_t.col(1);

  StanceLegRows rows;
  IkResult ik = kin.SolveFootIk(foot_B, seed, ws);
  if (!OnNominalBranch(ik.q, kin.nominal())) ik = kin.SolveFootIk(foot_B, ws);
  rows.q = ik.q;
  rows.reached = ik.ok();
  // Joints: q(dv) = q + J^-1 (residual + D dv), the residual being what IK left (nonzero when the
  // pose is out of reach or limits, so the rows then pull the body back to where it is reachable).
  const Eigen::Matrix3d jac = kin.FootJacobian(ik.q, ws);
  const double scale = jac.colwise().norm().prod();
  const bool regular = std::abs(jac.determinant()) > kSingularDet * scale;
  Eigen::Matrix<double, 3, 4> dq = Eigen::Matrix<double, 3, 4>::Zero();
  if (regular) {
    const Eigen::Matrix3d jac_inv = jac.inverse();
    const Eigen::Vector3d q_at = ik.q + jac_inv * (foot_B - kin.FootPosition(ik.q, ws));
    dq = jac_inv * d;
    const std::array<Eigen::Vector3d, 2> bent{jac_inv * bends_B[0], jac_inv * bends_B[1]};
    for (int j = 0; j < 3; ++j) {
      const Bulge bulge = BulgeOf(bent[0][j], bent[1][j]);
      SetRow(&rows, j, dq.row(j).transpose(), kin.lower()[j] + margins.joint + bulge.down - q_at[j],
             kin.upper()[j] - margins.joint - bulge.up - q_at[j]);
    }
  } else {
    for (int j = 0; j < 3; ++j) SetRow(&rows, j, Eigen::Vector4d::Zero(), 0.0, 0.0);
  }
  rows.dq = dq;
  // Extension: the flexion joint to foot distance within the knee's range. (The distance from the
  // hip's first joint is no bound: how far a leg reaches from there depends on the direction,
  // through the offsets between the first two joints.) The flexion joint turns with the first
  // joint, which moves it by d flex / d q0 times q0's change.
  const Eigen::Vector3d flexion = kin.FlexionPosition(ik.q, ws);
  // Read while the workspace holds the chain at ik.q: the flexion joint's derivative below moves it.
  const AxisDistance axis = AxisDistanceOf(kin, ws, ik.q, foot_B);
  const Eigen::Vector3d span = foot_B - flexion;
  const double length = span.norm();
  Eigen::Vector4d grad = Eigen::Vector4d::Zero();
  Bulge bulge;
  if (length > 1e-9) {
    const Eigen::Vector3d u = span / length;
    bulge = BulgeOf(u.dot(bends_B[0]), u.dot(bends_B[1]));
    grad = (u.transpose() * d).transpose();
    if (regular) {
      const Eigen::Vector3d turned = kin.FlexionPosition(ik.q + Eigen::Vector3d(kTurnStep, 0.0, 0.0), ws);
      grad -= u.dot((turned - flexion) / kTurnStep) * dq.row(0).transpose();
    }
  }
  SetRow(&rows, 3, grad, kin.extension().lo + margins.reach + bulge.down - length,
         kin.extension().hi - margins.reach - bulge.up - length);
  // The axis distance: at least the leg plane's offset and the reach (or axis) margin, the swing's
  // bulge toward the axis further out. Its upper side is loose: the extension row bounds the reach.
  if (axis.valid) {
    const Bulge toward = BulgeOf(axis.out.dot(bends_B[0]), axis.out.dot(bends_B[1]));
    const double keep = std::max(margins.reach, margins.axis);
    SetRow(&rows, 4, (axis.out.transpose() * d).transpose(), axis.offset + keep + toward.down - axis.distance,
           kin.reach().hi - axis.distance);
  } else {
    SetRow(&rows, 4, Eigen::Vector4d::Zero(), 0.0, 0.0);
  }
  return rows;
}

}  // namespace stairplan
