#include "planning/simulation/plan_executor.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <Eigen/Dense>
#include <mujoco/mujoco.h>

#include "collision/stance_check.h"
#include "planning/plan_pipeline.h"
#include "planning/simulation/body_reference.h"
#include "planning/simulation/plan_dynamics.h"
#include "planning/validation/traversal_validator.h"

namespace stairplan {
namespace {

constexpr double kMaxTargetSpeed = 20.0;  // joint target velocity cap [rad/s]: IK branch jumps are not velocities
constexpr double kMaxTargetAcceleration = 500.0;  // ... and acceleration cap [rad/s^2]
constexpr double kBlendTime = 0.1;        // a leg's aim moves between planned and measured body over this [s]

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

struct PlanExecutor::LegState {
  int kin = 0;                              // index in kinematics_
  std::string name;
  std::array<int, 3> qpos{}, dof{}, motor{};
  std::array<double, 3> effort{};
  int foot_body = -1;
  int foot_geom = -1;                       // the foot's sphere geom, -1 when it has none
  int knee_body = -1;                       // the body whose origin is the knee joint
  int hip_body = -1;                        // ... the hip joint
  double foot_radius = 0.0;
  Eigen::Vector3d contact_F = Eigen::Vector3d::Zero();  // a foot without a sphere geom: its contact sphere's centre in the foot frame
  bool stance = true;
  Eigen::Vector3d foothold_W = Eigen::Vector3d::Zero();  // where the stance foot stands
  bool stance_measured = false;             // stance_start_W holds where this stance began
  Eigen::Vector3d stance_start_W = Eigen::Vector3d::Zero();
  int step = -1;                            // the footstep being swung, -1 in stance
  int next = 0;                             // next entry of leg_steps_
  std::unique_ptr<SwingTrajectory> swing;
  Eigen::Vector3d q_target = Eigen::Vector3d::Zero();
  Eigen::Vector3d q_target_prev = Eigen::Vector3d::Zero();
  Eigen::Vector3d qd_target_prev = Eigen::Vector3d::Zero();
  bool has_target = false;
  double t_switch = -1e9;                   // plan time of the last liftoff or touchdown [s]
  double swing_t0 = 0.0, swing_t1 = 1.0;    // the swing's timing; a response re-times it [s, plan time]
  double swing_apex = 0.0;                  // the current swing's apex height [m]
  Eigen::Vector3d swing_target_W = Eigen::Vector3d::Zero();
  std::optional<ImpactKind> foot_impact;    // this step's classification of the foot's external force
  double foot_force = 0.0;                  // its magnitude [N]
  double t_first_contact = -1.0;            // the contact list's start of this swing's latest contact [s]
  bool link_touching = false;               // any link of this leg touches the stairs in the contact list
  bool was_touching = false;                // ... did at the previous step
  double t_recorded = -1e9;                 // the last impact recorded in this swing [s]
  double t_responded = -1e9;                // the last response carried out in this swing [s]
  bool scuffed = false;                     // a liftoff scuff was recorded in this swing
  int responses = 0;                        // responses in this swing
};

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
    FootLanding landing;
    landing.leg = leg.name;
    landing.t_planned = f.t_touchdown;
    landing.t_contact = touched ? tp : -1.0;
    landing.touched = touched;
    landing.target_W = f.position_W;
    landing.landed_W = FootContactPoint(leg);
    landing.error_m = (landing.landed_W - f.position_W).head<2>().norm();
    landing.stair = map_.StairAt(landing.landed_W.head<2>());
    landing.in_step_region = touched && landing.stair >= 0 &&
                             std::abs(map_.stair(landing.stair).z - landing.landed_W.z()) < 0.02 &&
                             map_.InStepRegion(landing.stair, landing.landed_W.head<2>(), 1e-6);
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
      outcome_.impacts.push_back(record);
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
    foot.max_normal = load[i] * 3.0 * mass_ * 9.81;
    // The ground pushes the foot with f: the joints hold it with -J^T f (base frame).
    foot.torque_map = -kin.FootJacobian(q, lws).transpose() * r_measured.transpose();
    const Eigen::Vector3d effort = settings_.stance.torque_use * Eigen::Vector3d(leg.effort[0], leg.effort[1], leg.effort[2]);
    foot.torque_lo = -effort - own_torque[i];
    foot.torque_hi = effort - own_torque[i];
  }
  if (!started) return;

  // The stance feet carry the wrench that moves the body as planned (the plan's acceleration fed
  // forward, PD on the measured base pose and velocity, gravity), distributed by the stance-force
  // QP: forces in their friction pyramids and the motors' room, never pulling, the moments of all
  // force components about the centre of mass included. A foot takes its load over
  // load_ramp_time after touchdown and gives it up over the same time before its liftoff.
  const double ts = settings_.time_scale;
  const bool moving = tp > 0.0 && tp < plan_.duration();
  const Eigen::Vector3d a_plan = moving ? Eigen::Vector3d(reference.acceleration_W / (ts * ts)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d v_plan = moving ? Eigen::Vector3d(reference.velocity_W / ts) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d v(d->qvel[0], d->qvel[1], d->qvel[2]);
  const Eigen::Vector3d omega_W = r_measured * Eigen::Vector3d(d->qvel[3], d->qvel[4], d->qvel[5]);
  const Eigen::Vector3d kp(settings_.xy_kp, settings_.xy_kp, settings_.height_kp);
  const Eigen::Vector3d kd(settings_.xy_kd, settings_.xy_kd, settings_.height_kd);
  const Eigen::Vector3d force_W =
      mass_ * (Eigen::Vector3d(0, 0, 9.81) + settings_.acceleration_feedforward * a_plan +
               kp.cwiseProduct(planned.position_W - measured.position_W) + kd.cwiseProduct(v_plan - v));
  const Eigen::AngleAxisd rotation_error(planned.ToIsometry().linear() * r_measured.transpose());
  const Eigen::Vector3d pitch_axis_W(-std::sin(planned.yaw), std::cos(planned.yaw), 0.0);
  const Eigen::Vector3d omega_plan_W =
      moving ? Eigen::Vector3d((reference.pitch_rate * pitch_axis_W + reference.yaw_rate * Eigen::Vector3d::UnitZ()) / ts)
             : Eigen::Vector3d::Zero();
  const Eigen::Vector3d moment_W =
      CompositeInertia() * (settings_.attitude_kp * rotation_error.angle() * rotation_error.axis() +
                            settings_.attitude_kd * (omega_plan_W - omega_W));
  const double* com = d->subtree_com + 3 * base_body_;
  std::array<Eigen::Vector3d, 4> force;
  if (!force_qp_.Solve(feet, Eigen::Vector3d(com[0], com[1], com[2]), force_W, moment_W, force)) {
    ++outcome_.force_qp_failures;
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

void PlanExecutor::RobotContact(double tp, const mjContact& con) {
  if (settings_.impact.source != ImpactSource::kContacts || con.dist > 0.0) return;
  const mjModel* m = world_->model();
  const int b1 = m->geom_bodyid[con.geom1], b2 = m->geom_bodyid[con.geom2];
  const int l1 = body_leg_[static_cast<std::size_t>(b1)], l2 = body_leg_[static_cast<std::size_t>(b2)];
  for (const auto& [mine, other, body, other_body] : {std::tuple{l1, l2, b1, b2}, std::tuple{l2, l1, b2, b1}}) {
    if (mine < 0 || legs_[static_cast<std::size_t>(mine)].stance) continue;
    const LegState& leg = legs_[static_cast<std::size_t>(mine)];
    const std::string link = mj_id2name(m, mjOBJ_BODY, body);
    if (other < 0 && (other_body == base_body_ || m->body_parentid[other_body] == 0)) {
      Respond(static_cast<std::size_t>(mine), ImpactKind::kThighAgainstBody, tp, link, 0.0);
    } else if (other >= 0 && other != mine) {
      const LegState& contra = legs_[static_cast<std::size_t>(other)];  // contralateral or not
      const ImpactKind kind =
          contra.name[0] == leg.name[0]
              ? ImpactKind::kIpsilateralStrike
              : ClassifyContralateral(FootContactPoint(leg), FootContactPoint(contra), leg.name[0] == 'L', MeasuredPose().yaw);
      Respond(static_cast<std::size_t>(mine), kind, tp, link, 0.0);
    }
  }
}

double PlanExecutor::SwingPhase(const LegState& leg, double tp) const {
  return (tp - leg.swing_t0) / std::max(leg.swing_t1 - leg.swing_t0, 1e-6);
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
    if (settings_.impact.source == ImpactSource::kTorqueResidual && leg.foot_impact != ImpactKind::kTouchdown) {
      // The residual does not say what the foot hit: the robot's own kinematics tell a strike on
      // another leg's shank from a trip on the stairs (a foot pushed up late in its swing has landed).
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

void PlanExecutor::Reswing(LegState& leg, double tp, const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W,
                           double apex_z) {
  leg.swing = std::make_unique<SwingTrajectory>(from_W, to_W, apex_z, settings_.swing);
  leg.swing_apex = apex_z;
  leg.swing_target_W = to_W;
  leg.swing_t1 = std::max(leg.swing_t1, tp + settings_.impact.min_reswing_time);
  leg.swing_t0 = tp;
}

void PlanExecutor::Respond(std::size_t i, ImpactKind kind, double tp, const std::string& link, double force) {
  LegState& leg = legs_[i];
  // One answer per impact: a foot pressed on an obstacle is the same impact until the response
  // has had time to act.
  constexpr double kRefractory = 0.1;
  constexpr int kMaxResponses = 3;
  if (tp - leg.t_recorded < kRefractory || tp - leg.t_responded < kRefractory) return;
  leg.t_recorded = tp;
  const BodyPose body = MeasuredPose();
  ImpactEvent event;
  event.kind = kind;
  event.leg = leg.name;
  event.swing_phase = std::clamp(SwingPhase(leg, tp), 0.0, 1.0);
  event.body_yaw = body.yaw;
  event.target_W = leg.swing_target_W;
  event.target_stair = map_.StairAt(event.target_W.head<2>());
  event.swing_foot_W = FootContactPoint(leg);
  for (const LegState& other : legs_) {
    if (other.name[1] == leg.name[1] && other.name[0] != leg.name[0]) event.contralateral_foot_W = FootContactPoint(other);
  }
  const ImpactResponse response = RespondToImpact(event, map_, settings_.impact.response);
  ImpactRecord record;
  record.t = tp;
  record.t_contact = leg.t_first_contact;
  record.leg = leg.name;
  record.kind = kind;
  record.source = settings_.impact.source;
  record.response = response.kind;
  record.link = link;
  record.swing_phase = event.swing_phase;
  record.force_n = force;
  record.reason = response.reason;
  outcome_.impacts.push_back(record);
  if (!settings_.impact.respond || leg.responses >= kMaxResponses || response.kind == ResponseKind::kProceed ||
      response.kind == ResponseKind::kClassifyStance) {
    return;
  }
  leg.t_responded = tp;
  ++leg.responses;
  const Eigen::Vector3d foot = event.swing_foot_W;
  Eigen::Vector3d back = leg.swing_target_W - foot;
  back.z() = 0.0;
  back = back.norm() > 1e-9 ? Eigen::Vector3d(-back.normalized()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d retracted = foot + settings_.impact.retract_distance * back;
  switch (response.kind) {
    case ResponseKind::kElevateFoot:  // draw back, lift higher than what stopped it, go on to the target
      Reswing(leg, tp, retracted, leg.swing_target_W, std::max(leg.swing_apex, foot.z()) + response.extra_swing_height);
      break;
    case ResponseKind::kTouchdownNow: {  // go down where the foot is, clear of what it hit
      Eigen::Vector3d down = retracted;
      down.z() = response.target_W.z();  // the tread under the foot in the map
      Reswing(leg, tp, retracted, down, retracted.z());
      leg.swing_t1 = tp + 0.5 * settings_.impact.min_reswing_time;
      break;
    }
    case ResponseKind::kMoveKneeForward: {
      const Eigen::Vector3d forward(std::cos(body.yaw), std::sin(body.yaw), 0.0);
      Reswing(leg, tp, foot + response.knee_forward * forward, leg.swing_target_W, leg.swing_apex);
      break;
    }
    case ResponseKind::kAdjustStep:
    case ResponseKind::kAdjustStepRisky:
    case ResponseKind::kUntangle: {
      const Eigen::Vector3d from = response.waypoints_W.empty() ? foot : response.waypoints_W.front();
      Reswing(leg, tp, from, response.target_W, std::max(leg.swing_apex, response.target_W.z() + settings_.swing.min_lift));
      break;
    }
    default:
      break;
  }
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
