// The executor: plays a plan on the simulated robot. Every millisecond the plan's body pose and
// each foot's contact point (its foothold, or the point on its swing trajectory) become joint
// targets through our IK; joint PD with gravity compensation tracks them, and stance legs add the
// torques of their contact forces: the wrench that moves the body as planned (acceleration fed
// forward, feedback on the base pose) distributed over the stance feet by a small QP. Touchdown
// is driven by contact (US 2020/0324412 A1 ("Robotically negotiating stairs") [0055]): a swinging
// foot that touches the stairs in the second half of its swing becomes a stance foot where it
// touched. Impacts (US 2020/0324412 [0053]-[0068]) are detected from the joint-torque residual or
// from MuJoCo's contact list, classified, answered with RespondToImpact's response (a tripped foot
// draws back and lifts higher, or goes down at once; a foot that strikes the contralateral leg
// steps away from it; a foot down outside the step region hops into it), recorded in the outcome
// and told to an ImpactListener. Detection lives in executor_impact_detection.cc, responses in
// executor_impact_response.cc.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/plan.h"
#include "stairplan/simulation/body_reference.h"
#include "stairplan/simulation/impact_record.h"
#include "stairplan/simulation/mujoco_world.h"
#include "stairplan/simulation/sim_outcome.h"
#include "stairplan/simulation/sim_settings.h"
#include "stairplan/simulation/stance_force_qp.h"
#include "stairplan/simulation/torque_residual.h"

struct mjContact_;

namespace stairplan {

/// Called at every recorded frame (SimSettings::frame_interval) with the world in that state and
/// the plan time [s]: for drawing it (OffscreenRenderer), not for changing it.
using FrameCallback = std::function<void(MujocoWorld& world, double t)>;

/// Told each impact and response the executor records (touchdowns included), as it happens: the
/// event stream US 2020/0324412 [0053] sends to the body planner. It must not change the world.
using ImpactListener = std::function<void(const ImpactRecord& event)>;

/// Plays a plan on the simulated robot in MuJoCo and judges the run (see the file's top comment).
class PlanExecutor {
 public:
  /// Builds the world and places the robot on the plan's initial footholds. Throws
  /// std::invalid_argument when the plan has no body samples or names unknown legs, and
  /// std::runtime_error when MuJoCo rejects the model. `map` judges the landings (step regions).
  PlanExecutor(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const Plan& plan,
               const SimSettings& settings = {});
  ~PlanExecutor();
  PlanExecutor(const PlanExecutor&) = delete;
  PlanExecutor& operator=(const PlanExecutor&) = delete;

  /// Settles, executes the plan, holds, and judges. Call once.
  SimulationOutcome Run(const FrameCallback& on_frame = {});

  /// The simulated world.
  const MujocoWorld& world() const { return *world_; }

  /// Subscribes `listener` to the impacts of the next Run (replacing any earlier one).
  void SetImpactListener(ImpactListener listener) { impact_listener_ = std::move(listener); }

 private:
  struct LegState;

  double PlanTime() const;
  void UpdatePhases(double tp, const std::vector<bool>& foot_touching);
  void Control(double tp);
  bool CheckContacts(double tp, std::vector<bool>& foot_touching);
  /// Records how far each stance foot has moved from where its stance began (max_foot_slip_m).
  void MeasureSlip(double tp);
  Eigen::Vector3d FootContactPoint(const LegState& leg) const;
  BodyPose MeasuredPose() const;
  /// How much of a full load a leg may carry now: 0 in swing, rising after touchdown and falling
  /// before the next liftoff over load_ramp_time.
  double LoadShare(const LegState& leg, double tp) const;
  /// The whole robot's rotational inertia about its centre of mass, world frame [kg m^2].
  Eigen::Matrix3d CompositeInertia() const;
  /// The most a stance foot may carry at `share` of its full load [N]: full is three times the
  /// robot's weight.
  double FootLoadLimit(double share) const { return share * 3.0 * mass_ * 9.81; }
  /// A wrench on the body at its centre of mass, world frame.
  struct BodyWrench {
    Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   ///< [N]
    Eigen::Vector3d moment_W = Eigen::Vector3d::Zero();  ///< [N m]
  };
  /// The wrench the stance feet carry without the MPC: the plan's acceleration fed forward, PD on
  /// the measured pose and velocity, gravity.
  BodyWrench PdWrench(double tp, const BodyReferenceState& reference, const BodyPose& measured,
                      const Eigen::Matrix3d& r_measured) const;
  /// The stance forces from the convex MPC at plan time tp: re-solved every mpc_period of
  /// simulated time from the measured state along the plan's next knots, held in between (a foot
  /// that has lifted carries nothing).
  void MpcForces(double tp, const std::array<StanceForceQp::Foot, 4>& feet, std::array<Eigen::Vector3d, 4>& force);
  /// Classifies each swing foot's external force (torque residual or contact forces) into
  /// leg.foot_impact and answers trips and scuffs.
  void DetectFootImpacts(double tp);
  /// A contact between two robot links: a swing leg on another leg, a thigh on the body. Always the
  /// ground truth of when the leg was hit (t_first_contact); answered with source kContacts.
  void RobotContact(double tp, const mjContact_& con);
  /// The world's force on a swing leg's foot [N]: from the torque residual or the contact list.
  Eigen::Vector3d FootForce(const LegState& leg);
  /// RespondToImpact for `kind` on swing leg `i`, carried out and recorded; true when the swing changed.
  bool Respond(std::size_t i, ImpactKind kind, double tp, const std::string& link, double force);
  /// Appends `record` to the outcome and tells the listener.
  void RecordImpact(const ImpactRecord& record);
  /// The swing of leg `leg` replaced from now: from `from_W` to `to_W` over the apex, ending no
  /// earlier than min_reswing_time from now.
  void Reswing(LegState& leg, double tp, const Eigen::Vector3d& from_W, const Eigen::Vector3d& to_W, double apex_z);
  double SwingPhase(const LegState& leg, double tp) const;
  /// Height of `p_W` above the stairs under it and a little either way along `ahead_W` [m].
  double Clearance(const Eigen::Vector3d& p_W, const Eigen::Vector3d& ahead_W) const;
  /// The other leg whose shank (knee to foot) swing leg `i`'s foot is against, -1 for none.
  int LegNearFoot(std::size_t i) const;
  void RecordFrame(double tp);
  void Judge(double tp);

  const Staircase& stairs_;
  const ConstrainedMap& map_;
  const Plan& plan_;
  SimSettings settings_;
  RobotKinematics kinematics_;
  RobotWorkspace ws_;
  std::unique_ptr<MujocoWorld> world_;
  std::vector<LegState> legs_;
  std::vector<std::vector<int>> leg_steps_;  // per leg: footstep indices by liftoff
  double mass_ = 0.0;
  int base_body_ = -1;
  double kp_ = 0.0, kd_ = 0.0;
  StanceForceQp force_qp_;
  std::unique_ptr<ConvexMpc> mpc_;  // with StanceForceSource::kConvexMpc
  std::vector<MpcKnot> mpc_knots_;  // the horizon, sized once
  std::array<Eigen::Vector3d, 4> mpc_forces_{};  // the last solve's first knot
  double mpc_solved_at_ = -1.0;  // simulated time of the last solve
  std::vector<double> full_inertia_;  // MuJoCo's mass matrix, nv x nv, sized once
  std::vector<bool> stair_geom_;      // per MuJoCo geom: part of the stairs
  std::vector<int> body_leg_;         // per MuJoCo body: the index in legs_ of the leg it belongs to, -1 otherwise
  std::unique_ptr<TorqueResidual> residual_;
  SimulationOutcome outcome_;
  ImpactListener impact_listener_;
  bool fallen_ = false;
  bool running_ = false;  // false while placing the robot: targets only, no torques
};

/// One call: rebuilds the robot-aware map the plan was planned on (OptionsForPlan), executes the
/// plan, returns what happened. The sweep's `--simulate` and `stairplan simulate` use this.
SimulationOutcome Simulate(const RobotModel& robot, const Staircase& stairs, const Plan& plan,
                           const SimSettings& settings = {}, const FrameCallback& on_frame = {});

}  // namespace stairplan
