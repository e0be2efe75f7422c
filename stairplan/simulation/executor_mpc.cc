// PlanExecutor's stance forces from the convex MPC (StanceForceSource::kConvexMpc): the measured
// body, the plan's body and footholds over the horizon.
#include <algorithm>

#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

#include "stairplan/simulation/body_reference.h"
#include "stairplan/simulation/executor_leg_state.h"
#include "stairplan/simulation/plan_executor.h"

namespace stairplan {
namespace {

// Whether leg `steps` (its footstep indices by liftoff, `next` the entry after the last liftoff)
// stands at plan time t, and where: its planned foothold once it has landed there, `standing`
// (where it stands now) until its next liftoff.
bool PlannedFoothold(const Plan& plan, const std::vector<int>& steps, int next, bool stance_now,
                     const Eigen::Vector3d& standing, double t, Eigen::Vector3d& foothold) {
  foothold = standing;
  bool stance = stance_now;
  for (int s = std::max(stance_now ? next : next - 1, 0); s < static_cast<int>(steps.size()); ++s) {
    const Footstep& f = plan.footsteps[static_cast<std::size_t>(steps[static_cast<std::size_t>(s)])];
    if (t < f.t_liftoff) break;
    stance = t >= f.t_touchdown;
    if (stance) foothold = f.position_W;
  }
  return stance;
}

}  // namespace

void PlanExecutor::MpcForces(double tp, const std::array<StanceForceQp::Foot, 4>& feet,
                             std::array<Eigen::Vector3d, 4>& force) {
  const mjData* d = world_->data();
  const double now = world_->time();
  if (mpc_solved_at_ >= 0.0 && now - mpc_solved_at_ < settings_.mpc_period - 1e-9) {
    for (std::size_t i = 0; i < 4; ++i) force[i] = feet[i].max_normal > 0.0 ? mpc_forces_[i] : Eigen::Vector3d::Zero();
    return;
  }
  mpc_solved_at_ = now;
  const double ts = settings_.time_scale, dt = settings_.mpc.knot_dt, duration = plan_.duration();
  const BodyPose measured = MeasuredPose();
  const Eigen::Matrix3d r_measured = measured.ToIsometry().linear();
  const Eigen::Vector3d com(d->subtree_com[3 * base_body_], d->subtree_com[3 * base_body_ + 1], d->subtree_com[3 * base_body_ + 2]);
  const Eigen::Matrix3d inertia = CompositeInertia();
  MpcState state;
  state.position_W = measured.position_W;
  state.velocity_W = Eigen::Vector3d(d->qvel[0], d->qvel[1], d->qvel[2]);
  state.angular_velocity_W = r_measured * Eigen::Vector3d(d->qvel[3], d->qvel[4], d->qvel[5]);
  const BodyReferenceState reference_now = BodyReferenceAt(plan_.body, std::clamp(tp, 0.0, duration));
  const Eigen::AngleAxisd error(r_measured * reference_now.pose.ToIsometry().linear().transpose());
  state.attitude_error_W = error.angle() * error.axis();
  MpcMotors motors;
  for (std::size_t i = 0; i < 4; ++i) {
    motors.torque_map[i] = feet[i].torque_map;
    motors.torque_lo[i] = feet[i].torque_lo;
    motors.torque_hi[i] = feet[i].torque_hi;
  }
  for (int k = 0; k < settings_.mpc.knots; ++k) {
    MpcKnot& knot = mpc_knots_[static_cast<std::size_t>(k)];
    const double t = tp + k * dt / ts;
    const bool moving = t > 0.0 && t < duration;
    const BodyReferenceState r = BodyReferenceAt(plan_.body, std::clamp(t, 0.0, duration));
    knot.position_W = k == 0 ? measured.position_W : r.pose.position_W;
    knot.velocity_W = moving ? Eigen::Vector3d(r.velocity_W / ts) : Eigen::Vector3d::Zero();
    knot.angular_velocity_W = moving ? Eigen::Vector3d(r.AngularVelocityW() / ts) : Eigen::Vector3d::Zero();
    knot.com_offset_W = com - measured.position_W;
    knot.inertia_W = inertia;
    for (std::size_t i = 0; i < 4; ++i) {
      if (k == 0) {
        knot.feet_W[i] = feet[i].position_W;
        knot.max_normal[i] = feet[i].max_normal;
        continue;
      }
      const LegState& leg = legs_[i];
      const bool stance = PlannedFoothold(plan_, leg_steps_[i], leg.next, leg.stance, feet[i].position_W, t, knot.feet_W[i]);
      knot.max_normal[i] = stance ? FootLoadLimit(1.0) : 0.0;
    }
  }
  if (!mpc_->Solve(state, mpc_knots_.data(), motors, mpc_forces_)) ++outcome_.force_qp_failures;
  force = mpc_forces_;
}

}  // namespace stairplan
