#include "stairplan/simulation/plan_executor.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <mujoco/mujoco.h>

#include "stairplan/collision/stance_check.h"
#include "stairplan/pipeline/plan_pipeline.h"
#include "stairplan/simulation/body_reference.h"
#include "stairplan/simulation/executor_leg_state.h"
#include "stairplan/simulation/impact_detection.h"
#include "stairplan/simulation/plan_dynamics.h"
#include "stairplan/planning/validation/traversal_validator.h"

namespace stairplan {
namespace {

constexpr double kMaxTargetSpeed = 20.0;  // joint target velocity cap [rad/s]: IK branch jumps are not velocities
constexpr double kMaxTargetAcceleration = 500.0;  // ... and acceleration cap [rad/s^2]
constexpr double kBlendTime = 0.1;        // a leg's aim moves between planned and measured body over this [s]

bool UsesConvexMpc(StanceForceSource source, const std::optional<Gait>& gait) {
  if (source == StanceForceSource::kByGait) return gait && !IsQuasiStatic(*gait);
  return source == StanceForceSource::kConvexMpc;
}

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

PlanExecutor::PlanExecutor(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const Plan& plan,
                           const SimSettings& settings)
    : stairs_(stairs), map_(map), plan_(plan), settings_(settings), kinematics_(robot), ws_(kinematics_),
      force_qp_([&] {
        StanceForceSettings s = settings.stance;
        s.friction = settings.world.friction;
        return s;
      }()) {
  settings_.Validate();
  if (plan.body.empty()) throw std::invalid_argument("plan.body: no body samples to execute");
  if (plan.legs.size() != 4 || plan.initial_feet_W.size() != 4) {
    throw std::invalid_argument("plan.legs: a plan for four legs with four initial footholds is needed");
  }
  world_ = std::make_unique<MujocoWorld>(robot, stairs, settings_.world);
  const mjModel* m = world_->model();
  mjData* d = world_->data();
  mass_ = world_->RobotMass();
  base_body_ = mj_name2id(m, mjOBJ_BODY, robot.base_link().c_str());
  full_inertia_.assign(static_cast<std::size_t>(m->nv * m->nv), 0.0);
  if (UsesConvexMpc(settings_.stance_forces, plan.gait)) {
    ConvexMpcSettings mpc = settings_.mpc;
    mpc.friction = settings_.world.friction;
    mpc_ = std::make_unique<ConvexMpc>(mass_, mpc);
    mpc_knots_.resize(static_cast<std::size_t>(mpc.knots));
  }
  kp_ = settings_.kp_per_kg * mass_;
  kd_ = settings_.kd_per_kg * mass_;
  legs_.resize(4);
  leg_steps_.resize(4);
  for (int i = 0; i < 4; ++i) {
    const std::string& name = plan.legs[static_cast<std::size_t>(i)];
    LegState& leg = legs_[static_cast<std::size_t>(i)];
    leg.kin = kinematics_.LegIndex(name);  // throws for unknown legs
    leg.name = name;
    const LegModel& model = kinematics_.leg(leg.kin).model();
    for (std::size_t j = 0; j < 3; ++j) {
      leg.qpos[j] = world_->QposIndex(model.joint_names[j]);
      leg.dof[j] = world_->QvelIndex(model.joint_names[j]);
      leg.motor[j] = world_->MotorIndex(model.joint_names[j]);
      leg.effort[j] = settings_.world.effort_scale * (model.limits[j].effort > 0.0 ? model.limits[j].effort : 1e3);
    }
    leg.foot_body = mj_name2id(m, mjOBJ_BODY, model.foot_link.c_str());
    if (leg.foot_body < 0) throw std::invalid_argument("robot: no body for foot link " + model.foot_link);
    // A mesh foot's contact sphere (LegModel::foot_contact): radius 0 at its lowest point, or a
    // round foot's rolling sphere.
    leg.contact_F = model.foot_sphere_center;
    leg.foot_radius = model.foot_radius;
    for (int g = 0; g < m->ngeom; ++g) {
      if (m->geom_bodyid[g] == leg.foot_body && m->geom_type[g] == mjGEOM_SPHERE) {
        leg.foot_geom = g;
        leg.foot_radius = m->geom_size[3 * g];
        break;
      }
    }
    leg.foothold_W = plan.initial_feet_W[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < plan.footsteps.size(); ++k) {
      if (plan.footsteps[k].leg == name) leg_steps_[static_cast<std::size_t>(i)].push_back(static_cast<int>(k));
    }
    std::sort(leg_steps_[static_cast<std::size_t>(i)].begin(), leg_steps_[static_cast<std::size_t>(i)].end(),
              [&](int a, int b) { return plan.footsteps[static_cast<std::size_t>(a)].t_liftoff <
                                         plan.footsteps[static_cast<std::size_t>(b)].t_liftoff; });
  }
  stair_geom_.assign(static_cast<std::size_t>(m->ngeom), false);
  for (int g = 0; g < m->ngeom; ++g) {
    const char* name = mj_id2name(m, mjOBJ_GEOM, g);
    stair_geom_[static_cast<std::size_t>(g)] = name != nullptr && std::string(name).rfind("stair_", 0) == 0;
  }
  body_leg_.assign(static_cast<std::size_t>(m->nbody), -1);
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    body_leg_[static_cast<std::size_t>(legs_[i].foot_body)] = static_cast<int>(i);
    for (std::size_t j = 0; j < 3; ++j) {
      const int joint = mj_name2id(m, mjOBJ_JOINT, kinematics_.leg(legs_[i].kin).model().joint_names[j].c_str());
      if (joint >= 0) body_leg_[static_cast<std::size_t>(m->jnt_bodyid[joint])] = static_cast<int>(i);
      if (joint >= 0 && j == 2) legs_[i].knee_body = m->jnt_bodyid[joint];
      if (joint >= 0 && j == 0) legs_[i].hip_body = m->jnt_bodyid[joint];
    }
  }
  for (const Footstep& f : plan.footsteps) {
    if (std::find(plan.legs.begin(), plan.legs.end(), f.leg) == plan.legs.end()) {
      throw std::invalid_argument("plan.footsteps: unknown leg '" + f.leg + "'");
    }
  }
  // Start at the plan's first pose, a few millimetres up so that no foot starts inside a tread.
  Control(0.0);
  for (const LegState& leg : legs_) {
    for (std::size_t j = 0; j < 3; ++j) d->qpos[leg.qpos[j]] = leg.q_target(static_cast<Eigen::Index>(j));
  }
  const BodyPose start = BodyPoseAt(plan.body, 0.0);
  world_->SetBasePose(start.position_W + Eigen::Vector3d(0, 0, 0.003), start.yaw, start.pitch);
}

PlanExecutor::~PlanExecutor() = default;

double PlanExecutor::PlanTime() const { return (world_->time() - settings_.settle_time) / settings_.time_scale; }

BodyPose PlanExecutor::MeasuredPose() const {
  BodyPose pose;
  pose.position_W = world_->BasePosition();
  const Eigen::Vector3d rpy = world_->BaseRollPitchYaw();
  pose.roll = rpy.x();
  pose.pitch = rpy.y();
  pose.yaw = rpy.z();
  return pose;
}

Eigen::Vector3d PlanExecutor::FootContactPoint(const LegState& leg) const {
  const mjData* d = const_cast<MujocoWorld&>(*world_).data();
  if (leg.foot_geom < 0) {
    const double* p = d->xpos + 3 * leg.foot_body;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> rotation(d->xmat + 9 * leg.foot_body);
    return Eigen::Vector3d(p[0], p[1], p[2]) + rotation * leg.contact_F - leg.foot_radius * Eigen::Vector3d::UnitZ();
  }
  const double* p = d->geom_xpos + 3 * leg.foot_geom;
  return {p[0], p[1], p[2] - leg.foot_radius};
}

double PlanExecutor::LoadShare(const LegState& leg, double tp) const {
  if (!leg.stance) return 0.0;
  const double ramp = settings_.load_ramp_time / settings_.time_scale;  // in plan time
  if (ramp <= 0.0) return 1.0;
  double share = std::clamp((tp - leg.t_switch) / ramp, 0.0, 1.0);
  const std::vector<int>& steps = leg_steps_[static_cast<std::size_t>(&leg - legs_.data())];
  if (leg.next < static_cast<int>(steps.size())) {
    const double liftoff = plan_.footsteps[static_cast<std::size_t>(steps[static_cast<std::size_t>(leg.next)])].t_liftoff;
    share = std::min(share, std::clamp((liftoff - tp) / ramp, 0.0, 1.0));
  }
  return share;
}

Eigen::Matrix3d PlanExecutor::CompositeInertia() const {
  const mjModel* m = world_->model();
  const mjData* d = const_cast<MujocoWorld&>(*world_).data();
  const Eigen::Vector3d com(d->subtree_com[3 * base_body_], d->subtree_com[3 * base_body_ + 1],
                            d->subtree_com[3 * base_body_ + 2]);
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (int b = base_body_; b < m->nbody; ++b) {
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->ximat + 9 * b);
    const Eigen::Vector3d principal(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]);
    const Eigen::Vector3d p = Eigen::Vector3d(d->xipos[3 * b], d->xipos[3 * b + 1], d->xipos[3 * b + 2]) - com;
    inertia += r * principal.asDiagonal() * r.transpose() +
               m->body_mass[b] * (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose());
  }
  return inertia;
}

void PlanExecutor::UpdatePhases(double tp, const std::vector<bool>& foot_touching) {
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    LegState& leg = legs_[i];
    const std::vector<int>& steps = leg_steps_[i];
    if (leg.stance && leg.next < static_cast<int>(steps.size())) {
      const Footstep& f = plan_.footsteps[static_cast<std::size_t>(steps[static_cast<std::size_t>(leg.next)])];
      if (tp >= f.t_liftoff) {
        leg.stance = false;
        leg.stance_measured = false;
        leg.step = steps[static_cast<std::size_t>(leg.next)];
        ++leg.next;
        leg.t_switch = tp;
        leg.swing_t0 = f.t_liftoff;
        leg.swing_t1 = f.t_touchdown;
        leg.swing_target_W = f.position_W;
        leg.t_first_contact = -1.0;
        leg.t_recorded = -1e9;
        leg.t_responded = -1e9;
        leg.scuffed = false;
        leg.responses = 0;
        leg.foot_impact.reset();
        // The swing starts where the foot really is, and ends where the plan says.
        leg.swing = std::isfinite(f.swing_apex_z)
                        ? std::make_unique<SwingTrajectory>(leg.foothold_W, f.position_W,
                                                            std::max(f.swing_apex_z, leg.foothold_W.z() + settings_.swing.min_lift),
                                                            settings_.swing, f.swing_approach_share)
                        : std::make_unique<SwingTrajectory>(leg.foothold_W, f.position_W, stairs_, settings_.swing);
        leg.swing_apex = leg.swing->apex_z();
      }
    }
    if (leg.stance) continue;
    const Footstep& f = plan_.footsteps[static_cast<std::size_t>(leg.step)];
    const double phase = SwingPhase(leg, tp);
    const bool late_out = tp - leg.swing_t1 > settings_.late_descent_max / std::max(settings_.late_descent_speed, 1e-6) + 0.1;
    // Touchdown as the detector sees it ([0055]): an upward force from the touchdown phase on;
    // without a detector, any foot contact then.
    const bool touched = phase >= settings_.touchdown_phase &&
                         (settings_.impact.source == ImpactSource::kNone ? static_cast<bool>(foot_touching[i])
                                                                         : leg.foot_impact == ImpactKind::kTouchdown);
    if (!touched && !late_out) continue;
    // Down outside every step region (the stairs are not where the plan put them): the foot moves
    // into the region before it takes load.
    if (touched && settings_.impact.source != ImpactSource::kNone && !InStepRegionAt(map_, FootContactPoint(leg)) &&
        Respond(i, ImpactKind::kMisplacedTouchdown, tp, "foot", leg.foot_force)) {
      continue;
    }
    FootLanding landing;
    landing.leg = leg.name;
    landing.t_planned = f.t_touchdown;
    landing.t_contact = touched ? tp : -1.0;
    landing.touched = touched;
    landing.target_W = f.position_W;
    landing.landed_W = FootContactPoint(leg);
    landing.error_m = (landing.landed_W - f.position_W).head<2>().norm();
    landing.stair = map_.StairAt(landing.landed_W.head<2>());
    landing.in_step_region = touched && InStepRegionAt(map_, landing.landed_W);
    outcome_.landings.push_back(landing);
    if (touched && settings_.impact.source != ImpactSource::kNone) {
      ImpactRecord record;
      record.t = tp;
      record.t_contact = leg.t_first_contact;
      record.t_planned = f.t_touchdown;
      record.leg = leg.name;
      record.kind = ImpactKind::kTouchdown;
      record.source = settings_.impact.source;
      record.response = ResponseKind::kClassifyStance;
      record.link = world_->model()->names + world_->model()->name_bodyadr[leg.foot_body];
      record.swing_phase = phase;
      record.force_n = leg.foot_force;
      const double early = f.t_touchdown - tp;
      record.reason = std::abs(early) < 0.02 ? "touchdown on time"
                      : (early > 0.0 ? "touchdown early by " : "touchdown late by ") + std::to_string(std::abs(early)) + " s";
      record.at_W = landing.landed_W;
      record.target_W = f.position_W;
      record.executed = true;
      RecordImpact(record);
    }
    leg.stance = true;
    leg.t_switch = tp;
    leg.step = -1;
    leg.swing.reset();
    leg.foothold_W = landing.landed_W;
  }
}

void PlanExecutor::Control(double tp) {
  const mjModel* m = world_->model();
  mjData* d = world_->data();
  const double t_plan = std::clamp(tp, 0.0, plan_.duration());
  const BodyReferenceState reference = BodyReferenceAt(plan_.body, t_plan);
  const BodyPose& planned = reference.pose;
  const bool started = running_;
  const BodyPose measured = started ? MeasuredPose() : planned;
  // Swing legs aim from the measured body so that they land on their world targets even when the
  // body lags; stance legs aim from the planned body so that their PD pulls the body back on plan.
  // The share moves over kBlendTime after a liftoff or touchdown so that no target jumps.
  const auto aim_pose = [&](const LegState& leg) {
    const double ramp = std::clamp((tp - leg.t_switch) / kBlendTime, 0.0, 1.0);
    const double a = settings_.swing_pose_feedback * (leg.stance ? 1.0 - ramp : ramp);
    BodyPose pose = planned;
    pose.position_W += a * (measured.position_W - planned.position_W);
    pose.roll += a * WrapAngle(measured.roll - planned.roll);
    pose.pitch += a * WrapAngle(measured.pitch - planned.pitch);
    pose.yaw += a * WrapAngle(measured.yaw - planned.yaw);
    return pose;
  };

  // Each leg's joint targets (IK of its foothold or swing point from its aim pose) and its own
  // torques: PD towards the targets plus gravity and Coriolis compensation (qfrc_bias). A loaded
  // stance leg keeps only stance_pd_scale of its PD: its contact force does the carrying, and a
  // stiff PD would fight the force distribution. It stiffens again as it unloads.
  const Eigen::Matrix3d r_measured = measured.ToIsometry().linear();
  std::array<double, 4> load{};
  std::array<Eigen::Vector3d, 4> own_torque;
  std::array<StanceForceQp::Foot, 4> feet;
  if (started) mj_fullM(m, full_inertia_.data(), d->qM);
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    LegState& leg = legs_[i];
    const LegKinematics& kin = kinematics_.leg(leg.kin);
    LegWorkspace& lws = ws_.leg(leg.kin);
    Eigen::Vector3d contact = leg.foothold_W;
    if (!leg.stance && leg.swing) {
      const double phase = SwingPhase(leg, tp);
      contact = leg.swing->At(phase);
      if (phase > 1.0) {  // late: keep lowering until the foot finds the stairs
        contact.z() -= std::min(settings_.late_descent_speed * (tp - leg.swing_t1), settings_.late_descent_max);
      }
    }
    const BodyPose pose = aim_pose(leg);
    const Eigen::Isometry3d body_W = pose.ToIsometry();
    const Eigen::Isometry3d w_body = body_W.inverse();
    const Eigen::Vector3d seed = leg.has_target ? leg.q_target : kin.nominal();
    IkResult ik = kin.SolveFootIk(w_body * FootOriginForContact(kin.model(), contact, body_W.linear()), seed, lws, settings_.ik);
    if (!kin.model().foot_sphere_center.isZero()) {
      const Eigen::Matrix3d foot_rotation = body_W.linear() * kin.FootPose(ik.q, lws).linear();
      ik = kin.SolveFootIk(w_body * FootOriginForContact(kin.model(), contact, foot_rotation), ik.q, lws, settings_.ik);
    }
    leg.q_target_prev = leg.has_target ? leg.q_target : ik.q;
    leg.q_target = ik.q;
    leg.has_target = true;
    if (!started) continue;

    Eigen::Vector3d q, qd, bias;
    for (int j = 0; j < 3; ++j) {
      q(j) = d->qpos[leg.qpos[static_cast<std::size_t>(j)]];
      qd(j) = d->qvel[leg.dof[static_cast<std::size_t>(j)]];
      bias(j) = d->qfrc_bias[leg.dof[static_cast<std::size_t>(j)]];
    }
    const double dt = m->opt.timestep * settings_.time_scale;  // plan time per step
    const Eigen::Vector3d qd_target =
        ((leg.q_target - leg.q_target_prev) / dt).cwiseMax(-kMaxTargetSpeed).cwiseMin(kMaxTargetSpeed);
    const Eigen::Vector3d qdd_target = ((qd_target - leg.qd_target_prev) / m->opt.timestep)
                                           .cwiseMax(-kMaxTargetAcceleration)
                                           .cwiseMin(kMaxTargetAcceleration);
    leg.qd_target_prev = qd_target;
    load[i] = LoadShare(leg, tp);
    const double pd = 1.0 - load[i] * (1.0 - settings_.stance_pd_scale);
    // A swinging leg's own inertia times its target acceleration (the leg block of MuJoCo's mass
    // matrix): without it the PD lags the swing and a foot stepping down lands short and fast.
    Eigen::Matrix3d inertia;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) inertia(r, c) = full_inertia_[static_cast<std::size_t>(leg.dof[r] * m->nv + leg.dof[c])];
    }
    own_torque[i] = pd * (kp_ * (leg.q_target - q) + kd_ * (qd_target - qd)) + bias;
    if (!leg.stance) own_torque[i] += settings_.swing_inertia_feedforward * inertia * qdd_target;
    StanceForceQp::Foot& foot = feet[i];
    foot.position_W = FootContactPoint(leg);
    foot.max_normal = FootLoadLimit(load[i]);
    // The ground pushes the foot with f: the joints hold it with -J^T f (base frame).
    foot.torque_map = -kin.FootJacobian(q, lws).transpose() * r_measured.transpose();
    const Eigen::Vector3d effort = settings_.stance.torque_use * Eigen::Vector3d(leg.effort[0], leg.effort[1], leg.effort[2]);
    foot.torque_lo = -effort - own_torque[i];
    foot.torque_hi = effort - own_torque[i];
  }
  if (!started) return;

  std::array<Eigen::Vector3d, 4> force;
  if (mpc_) {
    MpcForces(tp, feet, force);
  } else {
    const double* com = d->subtree_com + 3 * base_body_;
    const BodyWrench wrench = PdWrench(tp, reference, measured, r_measured);
    if (!force_qp_.Solve(feet, Eigen::Vector3d(com[0], com[1], com[2]), wrench.force_W, wrench.moment_W, force)) {
      ++outcome_.force_qp_failures;
    }
  }

  for (std::size_t i = 0; i < legs_.size(); ++i) {
    const LegState& leg = legs_[i];
    const Eigen::Vector3d tau = own_torque[i] + feet[i].torque_map * force[i];
    for (std::size_t j = 0; j < 3; ++j) {
      const double demanded = tau(static_cast<Eigen::Index>(j));
      JointTorquePeak& peak = outcome_.torques[i * 3 + j];
      if (std::abs(demanded) > peak.peak) {
        peak.peak = std::abs(demanded);
        peak.t = tp;
      }
      d->ctrl[leg.motor[j]] = std::clamp(demanded, -leg.effort[j], leg.effort[j]);
    }
  }
}

PlanExecutor::BodyWrench PlanExecutor::PdWrench(double tp, const BodyReferenceState& reference, const BodyPose& measured,
                                                const Eigen::Matrix3d& r_measured) const {
  // The stance feet carry the wrench that moves the body as planned (the plan's acceleration fed
  // forward, PD on the measured base pose and velocity, gravity), distributed by the stance-force
  // QP: forces in their friction pyramids and the motors' room, never pulling, the moments of all
  // force components about the centre of mass included. A foot takes its load over
  // load_ramp_time after touchdown and gives it up over the same time before its liftoff.
  const mjData* d = world_->data();
  const BodyPose& planned = reference.pose;
  const double ts = settings_.time_scale;
  const bool moving = tp > 0.0 && tp < plan_.duration();
  const Eigen::Vector3d a_plan = moving ? Eigen::Vector3d(reference.acceleration_W / (ts * ts)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d v_plan = moving ? Eigen::Vector3d(reference.velocity_W / ts) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d v(d->qvel[0], d->qvel[1], d->qvel[2]);
  const Eigen::Vector3d omega_W = r_measured * Eigen::Vector3d(d->qvel[3], d->qvel[4], d->qvel[5]);
  const Eigen::Vector3d kp(settings_.xy_kp, settings_.xy_kp, settings_.height_kp);
  const Eigen::Vector3d kd(settings_.xy_kd, settings_.xy_kd, settings_.height_kd);
  BodyWrench wrench;
  wrench.force_W = mass_ * (Eigen::Vector3d(0, 0, 9.81) + settings_.acceleration_feedforward * a_plan +
                            kp.cwiseProduct(planned.position_W - measured.position_W) + kd.cwiseProduct(v_plan - v));
  const Eigen::AngleAxisd rotation_error(planned.ToIsometry().linear() * r_measured.transpose());
  const Eigen::Vector3d omega_plan_W = moving ? Eigen::Vector3d(reference.AngularVelocityW() / ts) : Eigen::Vector3d::Zero();
  wrench.moment_W = CompositeInertia() * (settings_.attitude_kp * rotation_error.angle() * rotation_error.axis() +
                                          settings_.attitude_kd * (omega_plan_W - omega_W));
  return wrench;
}

bool PlanExecutor::CheckContacts(double tp, std::vector<bool>& foot_touching) {
  std::fill(foot_touching.begin(), foot_touching.end(), false);
  for (LegState& leg : legs_) leg.link_touching = false;
  const mjModel* m = world_->model();
  const mjData* d = world_->data();
  const int base = base_body_;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    const char* n1 = mj_id2name(m, mjOBJ_GEOM, con.geom1);
    const char* n2 = mj_id2name(m, mjOBJ_GEOM, con.geom2);
    const bool s1 = n1 != nullptr && std::string(n1).rfind("stair_", 0) == 0;
    const bool s2 = n2 != nullptr && std::string(n2).rfind("stair_", 0) == 0;
    if (!s1 && !s2) {
      RobotContact(tp, con);
      continue;
    }
    if (s1 && s2) continue;
    const int robot_geom = s1 ? con.geom2 : con.geom1;
    const std::string stair = s1 ? n1 : n2;
    const int body = m->geom_bodyid[robot_geom];
    const bool touching = con.dist <= 0.0;  // farther ones are only within the detection margin
    const int owner = body_leg_[static_cast<std::size_t>(body)];
    if (touching && owner >= 0) {
      // The ground truth the detectors' latency is measured against: when this contact began.
      LegState& leg = legs_[static_cast<std::size_t>(owner)];
      if (!leg.stance && !leg.link_touching && !leg.was_touching) leg.t_first_contact = tp;
      leg.link_touching = true;
    }
    bool foot = false;
    for (std::size_t i = 0; i < legs_.size(); ++i) {
      if (legs_[i].foot_body == body) {
        foot_touching[i] = foot_touching[i] || touching;
        foot = true;
      }
    }
    if (foot) continue;
    const std::string link = mj_id2name(m, mjOBJ_BODY, body);
    if (touching && owner >= 0 && settings_.impact.source == ImpactSource::kContacts && !legs_[static_cast<std::size_t>(owner)].stance) {
      const LegState& leg = legs_[static_cast<std::size_t>(owner)];
      const int hip = m->body_parentid[m->body_parentid[leg.foot_body]];
      const Eigen::Vector3d hip_W(d->xpos[3 * hip], d->xpos[3 * hip + 1], d->xpos[3 * hip + 2]);
      const Eigen::Vector3d at(con.pos[0], con.pos[1], con.pos[2]);
      Respond(static_cast<std::size_t>(owner), ClassifyLegLinkOnStairs(at, hip_W, MeasuredPose().yaw), tp, link, 0.0);
    }
    if (con.dist < outcome_.min_link_clearance_m) {
      outcome_.min_link_clearance_m = con.dist;
      outcome_.closest_link = link + " to " + stair;
    }
    if (!touching) continue;
    const double depth = -con.dist;
    auto it = std::find_if(outcome_.other_contacts.begin(), outcome_.other_contacts.end(),
                           [&](const LinkContact& l) { return l.link == link; });
    if (it == outcome_.other_contacts.end()) {
      outcome_.other_contacts.push_back({link, stair, tp, depth, 0});
      it = outcome_.other_contacts.end() - 1;
    }
    it->max_depth = std::max(it->max_depth, depth);
    ++it->steps;
    // Only the body's own geoms make a fall; a shin on a nosing is reported, not judged here.
    if ((body == base || m->body_parentid[body] == 0) && !fallen_) {
      fallen_ = true;
      outcome_.status = SimStatus::kFall;
      std::ostringstream cause;
      cause << "body " << link << " touched " << stair << " at t=" << tp << " s";
      outcome_.cause = cause.str();
    }
  }
  for (LegState& leg : legs_) leg.was_touching = leg.link_touching;
  return fallen_;
}

double PlanExecutor::SwingPhase(const LegState& leg, double tp) const {
  return (tp - leg.swing_t0) / std::max(leg.swing_t1 - leg.swing_t0, 1e-6);
}

void PlanExecutor::MeasureSlip(double tp) {
  for (LegState& leg : legs_) {
    if (!leg.stance) continue;
    const Eigen::Vector3d foot = FootContactPoint(leg);
    if (!leg.stance_measured) {
      leg.stance_start_W = foot;
      leg.stance_measured = true;
      continue;
    }
    const double slip = (foot - leg.stance_start_W).head<2>().norm();
    if (slip > outcome_.max_foot_slip_m) {
      outcome_.max_foot_slip_m = slip;
      outcome_.slipped_leg = leg.name;
      outcome_.slip_t = tp;
    }
  }
}

void PlanExecutor::RecordFrame(double tp) {
  const mjModel* m = world_->model();
  const mjData* d = world_->data();
  SimFrame frame;
  frame.t = tp;
  const BodyPose measured = MeasuredPose();
  const BodyPose planned = BodyPoseAt(plan_.body, std::clamp(tp, 0.0, plan_.duration()));
  frame.base_W = measured.position_W;
  frame.base_rpy = {measured.roll, measured.pitch, measured.yaw};
  frame.planned_W = planned.position_W;
  frame.planned_pitch = planned.pitch;
  for (const LegState& leg : legs_) {
    frame.stance.push_back(leg.stance);
    frame.legs.push_back(leg.name);
    frame.joint_q.emplace_back(d->qpos[leg.qpos[0]], d->qpos[leg.qpos[1]], d->qpos[leg.qpos[2]]);
  }
  for (int b = 1; b < m->nbody; ++b) {
    frame.bodies.emplace_back(d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]);
    frame.parents.push_back(m->body_parentid[b] - 1);
  }
  for (const LegState& leg : legs_) {
    if (leg.foot_geom < 0) continue;
    const double* p = d->geom_xpos + 3 * leg.foot_geom;
    frame.feet.emplace_back(p[0], p[1], p[2]);
    frame.foot_radii.push_back(leg.foot_radius);
  }
  outcome_.frames.push_back(std::move(frame));
}

void PlanExecutor::Judge(double tp) {
  const BodyPose measured = MeasuredPose();
  const BodyPose planned = BodyPoseAt(plan_.body, std::clamp(tp, 0.0, plan_.duration()));
  if (!measured.position_W.allFinite()) {
    fallen_ = true;
    outcome_.status = SimStatus::kFall;
    outcome_.cause = "the simulation diverged at t=" + std::to_string(tp) + " s";
    return;
  }
  const double roll = std::abs(measured.roll);
  const double pitch_error = std::abs(WrapAngle(measured.pitch - planned.pitch));
  outcome_.max_roll = std::max(outcome_.max_roll, roll);
  outcome_.max_pitch_error = std::max(outcome_.max_pitch_error, pitch_error);
  if (tp >= 0.0) {
    outcome_.max_height_error =
        std::max(outcome_.max_height_error, std::abs(measured.position_W.z() - planned.position_W.z()));
  }
  if (roll > settings_.fall_angle || pitch_error > settings_.fall_angle) {
    fallen_ = true;
    outcome_.status = SimStatus::kFall;
    std::ostringstream cause;
    cause << (roll > settings_.fall_angle ? "roll " : "pitch error ")
          << (roll > settings_.fall_angle ? roll : pitch_error) << " rad at t=" << tp << " s";
    outcome_.cause = cause.str();
  }
}

SimulationOutcome PlanExecutor::Run(const FrameCallback& on_frame) {
  const auto start = std::chrono::steady_clock::now();
  outcome_ = SimulationOutcome{};
  mpc_solved_at_ = -1.0;
  outcome_.min_link_clearance_m = settings_.world.detect_margin;
  running_ = true;
  for (const LegState& leg : legs_) {
    const LegModel& model = kinematics_.leg(leg.kin).model();
    for (std::size_t j = 0; j < 3; ++j) outcome_.torques.push_back({model.joint_names[j], 0.0, leg.effort[j], 0.0, 0.0});
  }
  const double t_final = plan_.duration() + settings_.hold_time / settings_.time_scale;
  std::vector<bool> touching(legs_.size(), false);
  residual_ = std::make_unique<TorqueResidual>(world_->model(), world_->data());
  double next_frame = -settings_.settle_time / settings_.time_scale;
  while (!fallen_) {
    const double tp = PlanTime();
    if (tp > t_final) break;
    if (settings_.frame_interval > 0.0 && tp >= next_frame - 1e-9) {
      RecordFrame(tp);
      if (on_frame) on_frame(*world_, tp);
      next_frame += settings_.frame_interval;
    }
    if (tp >= 0.0) UpdatePhases(tp, touching);
    Control(tp);
    world_->Step();
    ++outcome_.sim_steps;
    residual_->Update(world_->model(), world_->data());
    if (CheckContacts(PlanTime(), touching)) break;
    if (PlanTime() >= 0.0) DetectFootImpacts(PlanTime());
    // From the plan's start on: while settling the feet find the treads.
    if (PlanTime() >= 0.0) MeasureSlip(PlanTime());
    Judge(PlanTime());
  }
  const double tp = PlanTime();
  outcome_.t_end = tp;
  const BodyPose measured = MeasuredPose();
  outcome_.final_base_W = measured.position_W;
  outcome_.final_rpy = {measured.roll, measured.pitch, measured.yaw};
  const BodyState& last = plan_.body.back();
  outcome_.final_error_m = (measured.position_W - Eigen::Vector3d(last.x, last.y, last.z)).norm();
  if (!fallen_) {
    if (outcome_.final_error_m <= settings_.goal_tolerance) {
      outcome_.status = SimStatus::kSuccess;
    } else {
      outcome_.status = SimStatus::kStalled;
      std::ostringstream cause;
      cause << "the base ended " << outcome_.final_error_m << " m from the plan's final pose";
      outcome_.cause = cause.str();
    }
  }
  for (JointTorquePeak& peak : outcome_.torques) {
    peak.ratio = peak.effort_limit > 0.0 ? peak.peak / peak.effort_limit : 0.0;
    outcome_.max_torque_ratio = std::max(outcome_.max_torque_ratio, peak.ratio);
  }
  outcome_.time_scale = settings_.time_scale;
  outcome_.stance_forces = mpc_ ? StanceForceSource::kConvexMpc : StanceForceSource::kWrench;
  const ZmpMargin zmp = PlanZmpMargin(kinematics_.robot(), plan_, settings_.time_scale);
  outcome_.plan_zmp_margin_m = zmp.margin_m;
  outcome_.plan_zmp_t = zmp.t;
  outcome_.plan_max_acceleration = zmp.max_acceleration;
  // A fall the plan asked for: its ZMP left the support polygon before the robot fell.
  const ZmpMargin before_fall = PlanZmpMargin(kinematics_.robot(), plan_, settings_.time_scale, 0.005, tp);
  if (outcome_.status == SimStatus::kFall && before_fall.margin_m < 0.0) {
    std::ostringstream why;
    why << "; before it, at this pace, the plan's ZMP left its support polygon by " << -before_fall.margin_m
        << " m (t=" << before_fall.t << " s; body acceleration " << before_fall.max_acceleration
        << " m/s^2): more than the feet can carry";
    outcome_.cause += why.str();
  }
  outcome_.sim_time_s = world_->time();
  outcome_.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome_.real_time_factor = outcome_.wall_time_s > 0.0 ? outcome_.sim_time_s / outcome_.wall_time_s : 0.0;
  return outcome_;
}

SimulationOutcome Simulate(const RobotModel& robot, const Staircase& stairs, const Plan& plan, const SimSettings& settings,
                           const FrameCallback& on_frame) {
  const ConstrainedMap map = BuildPipelineMap(robot, stairs, OptionsForPlan(plan));
  PlanExecutor executor(robot, stairs, map, plan, settings);
  return executor.Run(on_frame);
}

}  // namespace stairplan
