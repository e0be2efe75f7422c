// PlanExecutor's impact detection (seed 000 [0053]-[0068]): each swing foot's external force, from
// the joint-torque residual or MuJoCo's contact list, classified into the patent's kinds; contacts
// between robot links; the robot's own geometry telling a strike on another leg from a trip.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <Eigen/Dense>
#include <mujoco/mujoco.h>

#include "stairplan/simulation/executor_leg_state.h"
#include "stairplan/simulation/impact_detection.h"

namespace stairplan {

void PlanExecutor::RobotContact(double tp, const mjContact& con) {
  if (con.dist > 0.0) return;
  const mjModel* m = world_->model();
  const int b1 = m->geom_bodyid[con.geom1], b2 = m->geom_bodyid[con.geom2];
  const int l1 = body_leg_[static_cast<std::size_t>(b1)], l2 = body_leg_[static_cast<std::size_t>(b2)];
  for (const auto& [mine, other, body, other_body] : {std::tuple{l1, l2, b1, b2}, std::tuple{l2, l1, b2, b1}}) {
    if (mine < 0 || legs_[static_cast<std::size_t>(mine)].stance || other == mine) continue;
    LegState& leg = legs_[static_cast<std::size_t>(mine)];
    const bool on_body = other < 0 && (other_body == base_body_ || m->body_parentid[other_body] == 0);
    if (other < 0 && !on_body) continue;
    // The ground truth the detectors' latency is measured against, as for links on the stairs.
    if (!leg.link_touching && !leg.was_touching) leg.t_first_contact = tp;
    leg.link_touching = true;
    if (settings_.impact.source != ImpactSource::kContacts) continue;
    const std::string link = mj_id2name(m, mjOBJ_BODY, body);
    if (on_body) {
      Respond(static_cast<std::size_t>(mine), ImpactKind::kThighAgainstBody, tp, link, 0.0);
    } else {
      const LegState& contra = legs_[static_cast<std::size_t>(other)];  // contralateral or not
      const ImpactKind kind =
          contra.name[0] == leg.name[0]
              ? ImpactKind::kIpsilateralStrike
              : ClassifyContralateral(FootContactPoint(leg), FootContactPoint(contra), leg.name[0] == 'L', MeasuredPose().yaw);
      Respond(static_cast<std::size_t>(mine), kind, tp, link, 0.0);
    }
  }
}

Eigen::Vector3d PlanExecutor::FootForce(const LegState& leg) {
  const mjModel* m = world_->model();
  const mjData* d = world_->data();
  if (settings_.impact.source == ImpactSource::kContacts) {
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& con = d->contact[c];
      const bool first = m->geom_bodyid[con.geom1] == leg.foot_body;
      if (!first && m->geom_bodyid[con.geom2] != leg.foot_body) continue;
      if (!stair_geom_[static_cast<std::size_t>(first ? con.geom2 : con.geom1)]) continue;  // legs on legs: RobotContact
      mjtNum local[6];
      mj_contactForce(m, d, c, local);
      // The contact frame's rows are its normal (from geom1 to geom2) and two tangents.
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(con.frame);
      const Eigen::Vector3d on_geom2 = frame.transpose() * Eigen::Vector3d(local[0], local[1], local[2]);
      total += first ? Eigen::Vector3d(-on_geom2) : on_geom2;
    }
    return total;
  }
  // J^T f = tau_ext on the leg's joints; f in the base frame, by damped least squares: near a
  // straight leg the force along it moves no joint and is not seen.
  const LegKinematics& kin = kinematics_.leg(leg.kin);
  Eigen::Vector3d q, tau;
  for (int j = 0; j < 3; ++j) {
    q(j) = d->qpos[leg.qpos[static_cast<std::size_t>(j)]];
    tau(j) = residual_->at(leg.dof[static_cast<std::size_t>(j)]);
  }
  const Eigen::Matrix3d jac = kin.FootJacobian(q, ws_.leg(leg.kin));
  const Eigen::Vector3d f_B = (jac * jac.transpose() + 1e-4 * Eigen::Matrix3d::Identity()).ldlt().solve(jac * tau);
  return MeasuredPose().ToIsometry().linear() * f_B;
}

void PlanExecutor::DetectFootImpacts(double tp) {
  if (settings_.impact.source == ImpactSource::kNone) return;
  const double threshold = settings_.impact.force_threshold * mass_ * 9.81;
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    LegState& leg = legs_[i];
    leg.foot_impact.reset();
    if (leg.stance || !leg.swing) continue;
    const Eigen::Vector3d force = FootForce(leg);
    leg.foot_force = force.norm();
    const double phase = SwingPhase(leg, tp);
    const Eigen::Vector3d dir = leg.swing_target_W - leg.swing->At(0.0);
    leg.foot_impact = ClassifySwingFootForce(force, dir, phase, settings_.touchdown_phase, threshold, settings_.impact.scuff_phase);
    if (!leg.foot_impact) continue;
    // An upward push with the foot above the stairs is not a landing on them: it stands on something else.
    const bool on_stairs = Clearance(FootContactPoint(leg), dir) <= settings_.impact.touchdown_clearance;
    if (settings_.impact.source == ImpactSource::kTorqueResidual && (leg.foot_impact != ImpactKind::kTouchdown || !on_stairs)) {
      // The residual does not say what the foot hit: the robot's own kinematics tell a strike on
      // another leg's shank from a trip on the stairs (a foot pushed up late in its swing, on the
      // stairs, has landed).
      if (const int struck = LegNearFoot(i); struck >= 0) {
        const LegState& other = legs_[static_cast<std::size_t>(struck)];
        leg.foot_impact = other.name[0] == leg.name[0]
                              ? ImpactKind::kIpsilateralStrike
                              : ClassifyContralateral(FootContactPoint(leg), FootContactPoint(other), leg.name[0] == 'L',
                                                      MeasuredPose().yaw);
        Respond(i, *leg.foot_impact, tp, "foot", leg.foot_force);
        continue;
      }
    }
    if (settings_.impact.source == ImpactSource::kTorqueResidual && leg.foot_impact != ImpactKind::kTouchdown &&
        Clearance(FootContactPoint(leg), dir) > settings_.impact.near_stairs) {
      // The foot is clear of the stairs: what was hit is higher up the leg. A knee near the stairs
      // hit them; otherwise the thigh met the body.
      const mjData* d = world_->data();
      const auto position = [&](int body) { return Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]); };
      const Eigen::Vector3d knee = position(leg.knee_body);
      const bool knee_on_stairs = Clearance(knee, dir) < settings_.impact.near_stairs;
      leg.foot_impact = knee_on_stairs ? ClassifyLegLinkOnStairs(knee, position(leg.hip_body), MeasuredPose().yaw)
                                       : ImpactKind::kThighAgainstBody;
      Respond(i, *leg.foot_impact, tp, knee_on_stairs ? "knee" : "thigh", leg.foot_force);
      continue;
    }
    if (leg.foot_impact == ImpactKind::kLiftoffScuff && !leg.scuffed) {
      leg.scuffed = true;
      Respond(i, ImpactKind::kLiftoffScuff, tp, "foot", leg.foot_force);
    } else if (leg.foot_impact == ImpactKind::kTrip) {
      Respond(i, ImpactKind::kTrip, tp, "foot", leg.foot_force);
    }
  }
}

double PlanExecutor::Clearance(const Eigen::Vector3d& p_W, const Eigen::Vector3d& ahead_W) const {
  Eigen::Vector3d dir = ahead_W;
  dir.z() = 0.0;
  if (dir.norm() > 1e-9) dir.normalize();
  double top = -std::numeric_limits<double>::infinity();
  for (const double s : {-1.0, 0.0, 1.0}) {
    const Eigen::Vector3d q = p_W + s * settings_.impact.near_stairs * dir;
    const double z = stairs_.HeightAt(q.x(), q.y());
    if (std::isfinite(z)) top = std::max(top, z);
  }
  return p_W.z() - top;
}

int PlanExecutor::LegNearFoot(std::size_t i) const {
  const mjData* d = const_cast<MujocoWorld&>(*world_).data();
  const LegState& leg = legs_[i];
  const Eigen::Vector3d foot = FootContactPoint(leg) + Eigen::Vector3d(0.0, 0.0, leg.foot_radius);
  const auto position = [&](int body) { return Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]); };
  for (std::size_t k = 0; k < legs_.size(); ++k) {
    const LegState& other = legs_[k];
    if (k == i || other.knee_body < 0) continue;
    const Eigen::Vector3d other_foot = FootContactPoint(other) + Eigen::Vector3d(0.0, 0.0, other.foot_radius);
    if (DistanceToSegment(foot, position(other.knee_body), other_foot) < leg.foot_radius + settings_.impact.leg_strike_distance) {
      return static_cast<int>(k);
    }
  }
  return -1;
}

}  // namespace stairplan
