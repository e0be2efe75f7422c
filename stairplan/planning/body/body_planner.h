// The control-loop body planner (US 2020/0324412 A1 ("Robotically negotiating stairs")
// [0050]-[0052], claims 3-4): a receding-horizon QP over the body's height, pitch and forward and
// sideways weight shift, bounded by every stance leg's reach, by the height below which a leg would
// touch the stairs and by the support polygon the centre of mass must stay over (quasi-static
// gaits), re-linearised around the previous solution and re-solved warm once per cycle.
//
//   BodyPlanner planner(robot, stairs, map, PlanCrawlFootholds(robot, stairs, map), settings);  // once
//   BodyState state = planner.StartState();
//   for (double now = 0.0;; now += 0.003) {                  // every 3 ms
//     const BodyPlannerOutput& out = planner.Update(state, BodyCommand{}, now);
//     if (out.status == BodyPlanStatus::kStale) { /* out.knots is the shifted previous plan */ }
//     Track(out.knots, out.feet);                            // body references and foot targets
//   }
//
// Update() never allocates after the first call (warm-up) as long as the bounds it needs are
// cached; it throws only for misuse (non-finite state or time). Footsteps come from a footstep
// plan (the crawl planner or the step planner's offline driver).
#pragma once

#include <array>
#include <chrono>
#include <memory>
#include <vector>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/body/body_bounds.h"
#include "stairplan/planning/body/body_planner_settings.h"
#include "stairplan/planning/body/body_qp.h"
#include "stairplan/planning/body/com_estimate.h"
#include "stairplan/planning/body/foot_schedule.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/body/knot_row_cache.h"
#include "stairplan/planning/body/stance_leg_rows.h"
#include "stairplan/planning/com_model.h"
#include "stairplan/optim/solve_result.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

struct Clearance;

/// What the operator asks of the body on top of the plan.
struct BodyCommand {
  double height_offset = 0.0;  ///< added to the desired hip height [m]
  double pitch_offset = 0.0;   ///< added to the pitch reference [rad]
};


/// One leg's footstep target at the current time.
struct LegTarget {
  bool stance = true;  ///< in stance now (false: swinging)
  Eigen::Vector3d foot_W = Eigen::Vector3d::Zero();    ///< contact point now (interpolated in swing)
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< where the foot lands next (= foot_W in stance)
  double t_liftoff = 0.0;    ///< swing start (in stance: the next one, +inf when none)
  double t_touchdown = 0.0;  ///< swing end (in stance: the last one)
};

/// How long the parts of one Update() took [us].
struct BodyPlannerTimings {
  double bounds_us = 0.0;  ///< linearisation and bounds
  double solve_us = 0.0;   ///< the QP
  double total_us = 0.0;   ///< the whole Update
};

/// What one Update() produced: the body references over the horizon, the foot targets and how the cycle went.
struct BodyPlannerOutput {
  BodyPlanStatus status = BodyPlanStatus::kOk;  ///< how the cycle went
  optim::SolveStatus solve_status = optim::SolveStatus::kSolved;  ///< how the QP solve ended
  std::array<LegTarget, kBodyLegs> feet{};  ///< each leg's foothold or swing target now, in kinematics order
  std::vector<BodyState> knots;  ///< body references at now + k * knot_dt (sized once)
  /// Stance legs at knots 1.. whose bounds the new plan breaks: no valid hip height, or a row
  /// that gave way to the previous plan (rows never exclude the previous plan, the centre of the
  /// trust region, so the QP stays feasible while the cost pulls the plan back inside).
  int conflicts = 0;
  ///@{
  int conflict_knot = -1, conflict_leg = -1;  ///< the first one
  ///@}
  double next_violation = 0.0;   ///< how far the next knot breaks a stance leg's bound [m]
  /// With leg rows: the share of its linearisation point's violations knot 1, the one executed
  /// next, keeps (its relaxation, BodyQp::relax): 0 where every row holds there, 1 where the
  /// QP could mend none of them (a leg row or the support polygon the body cannot reach in time).
  double relaxation = 0.0;
  int iterations = 0;            ///< active-set changes
  int solves = 0;                ///< QPs solved in this Update (> 1 only at warm-up)
  /// With leg rows: knots linearised in this Update, and of those how many took their leg rows
  /// over from the last linearisation at the same instant (KnotRowCache).
  int linearised_knots = 0;
  int reused_knots = 0;  ///< see linearised_knots
  BodyPlannerTimings timings;  ///< how long the cycle's parts took
};

/// The receding-horizon body planner of a control loop (see the file's top comment for its use).
class BodyPlanner {
 public:
  /// Builds the bounds (KDL IK and FCL clearances) and the QP for `footsteps`' footholds. Throws
  /// std::invalid_argument naming the field or footstep for bad settings or a malformed plan.
  BodyPlanner(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map, const Plan& footsteps,
              const BodyPlannerSettings& settings = {});
  /// The same on the robot's kinematics built already.
  BodyPlanner(const RobotKinematics& kinematics, const Staircase& stairs, const ConstrainedMap& map,
              const Plan& footsteps, const BodyPlannerSettings& settings = {});
  /// The same with given bounds (tests use fakes).
  BodyPlanner(const RobotModel& robot, const Staircase& stairs, const Plan& footsteps,
              std::shared_ptr<BodyBounds> bounds, const BodyPlannerSettings& settings = {});

  /// One cycle at time `now` from the measured `state`. The first call (and the first after
  /// Reset()) converges the linearisation with up to warmup_solves QPs and has no budget.
  const BodyPlannerOutput& Update(const BodyState& state, const BodyCommand& command, double now);
  /// Forgets the previous plan.
  void Reset() { has_previous_ = false; }

  /// A state to start from: the neutral body over the initial feet at the desired hip height
  /// (with leg rows, the nearest height at which every leg stands within its limits and clear of
  /// the stairs).
  BodyState StartState() const;
  /// StartState() with the body where a robot stands (`standing_xy`, e.g. the alignment pose it
  /// walked to): the difference to the neutral body becomes the start's weight shifts, within
  /// their bounds.
  BodyState StartStateAt(const Eigen::Vector2d& standing_xy) const;
  /// The body reference at time t from the latest plan (interpolated between knots).
  BodyState Interpolate(double t) const;
  /// The latest cycle's output.
  const BodyPlannerOutput& output() const { return output_; }
  /// The footholds and each leg's stance and swing phases over time.
  const FootSchedule& schedule() const { return schedule_; }
  /// The settings it was built with.
  const BodyPlannerSettings& settings() const { return settings_; }
  /// The hip-height bounds the QP is linearised from.
  BodyBounds& bounds() { return *bounds_; }
  /// The QP solved every cycle (inputs and program, for inspection).
  BodyQp& qp() { return *qp_; }
  /// The desired hip height above the contact points [m].
  double desired_hip_height() const { return hip_height_; }
  /// Heading of the flight's travel in the world [rad].
  double yaw() const { return schedule_.yaw(); }
  /// The hip (first joint) of leg `leg` in the base frame.
  const Eigen::Vector3d& hip_B(int leg) const { return hips_B_[static_cast<std::size_t>(leg)]; }
  /// |pitch| of the flight's slope line [rad].
  double stairs_pitch() const { return stairs_pitch_; }
  ///@{
  /// The hip's offset from the body origin at `pitch`: vertical, and along the heading [m].
  double HipDz(int leg, double pitch) const;
  double HipDx(int leg, double pitch) const;
  ///@}

 private:
  // `built`: the robot's kinematics when the bounds have built them already (else built here).
  void Initialise(const RobotModel& robot, const Staircase& stairs, const RobotKinematics* built);
  // Fills the QP's inputs around the previous plan; returns the number of conflicting rows.
  void Linearise(const BodyState& state, const BodyCommand& command, double now);
  // The body pose at the trust region's centre v0 of a knot whose neutral body is at `neutral_xy`.
  BodyPose CentrePose(const Eigen::Vector2d& neutral_xy, const Eigen::Vector4d& v0) const;
  // Knot k's leg rows at the centre `at` (v0): taken over from the row cache when it holds them
  // (returns true), else linearised (StanceRows) and kept there.
  bool LegRows(int k, double t, const BodyPose& at, const Eigen::Vector4d& v0);
  // True when knot k's centre breaks one of its leg or clearance rows.
  bool KnotBreaksRows(int k) const;
  // The body height at knot k and `pitch` that meets the legs' height references on average.
  double ReferenceHeight(int k, double pitch) const;
  // The progress rows (with leg rows): the body's advance along the travel, knot to knot, is
  // negative only by what the QP's retreat variables pay for.
  void ProgressRows();
  // Bounds knot 1 so that the body executed a cycle ago, the state and knot 1 keep within the
  // acceleration limits.
  void KeepAccelerationAcrossCycles(const BodyState& state, double now);
  // Knot k's support rows: the COM estimate inside the polygon of the legs standing through
  // knots k-1..k+1, shrunk by the stability margin (rows free where no polygon applies).
  // `restored`: knot k's leg rows came from row_cache_ (its exact COM may too).
  void SupportRows(int k, double t, double pitch, const BodyPose& at, const Eigen::Vector4d& v0, bool restored);
  // Knot k's ZMP rows where two legs stand through knots k-1..k+1 (`foothold`: each leg's, -1 for
  // the others): the ZMP on the line between their feet.
  void DiagonalRows(int k, const std::array<int, kBodyLegs>& foothold);
  // With leg rows, after every knot's SupportRows: the rows hold the ZMP (COM - h/g COM'', the
  // pendulum as high as the hips) inside the polygon, BodyQp::ZmpStencil over knots k-1..k+1.
  void ZmpSupportRows(double now);
  // The COM at knot k without the weight shifts: from the leg rows' joints at the linearisation
  // point `at` (v0) when there are leg rows, else from the affine estimate.
  Eigen::Vector2d ComBase(int k, double t, double pitch, const Eigen::Vector2d& feet_sum, const BodyPose& at,
                          const Eigen::Vector4d& v0, bool restored);
  // Knot k's leg rows: every leg's joints, extension and clearance linearised at the pose `at`
  // (the trust region's centre), a stance leg's foot on its contact, a swing leg's on its swing
  // trajectory (rows free at knot 0 and without kinematics). t is the knot's instant.
  void StanceRows(int k, double t, const BodyPose& at, const Eigen::Vector4d& v0);
  // Leg l's rows (joints, extension, and the joint derivative its clearance rows read) at the
  // body pose `at` (rotation `body_rotation`), its foot on the contact `phase` gives (a swing
  // leg's on its swing trajectory), the IK started from `seed`.
  StanceLegRows LinearizeLeg(int l, const LegPhase& phase, const BodyPose& at, const Eigen::Matrix3d& body_rotation,
                             const Eigen::Vector3d& seed, const StanceLegMargins& margins);
  // How far leg l's foot strays at the middles of the knot intervals before and after instant t
  // from the chords between the knots (StanceLegMargins::foot_bends_W).
  std::array<Eigen::Vector3d, 2> FootBends(int l, double t) const;
  // Where leg l's foot contact point is at time t (on its foothold, or along its swing).
  Eigen::Vector3d FootAt(int l, double t) const;
  // Leg l's clearance row k of `into` (the knots' or the half-knots' rows) at the pose `at`: its
  // closest link point's distance to the stairs (FCL), linearised through `rows`' joint
  // derivative; free when the leg is far from them. A swing leg's foot contact shape is left out
  // (its path is the swing trajectory's), and its links keep more as its foot moves at time t
  // (the row's instant) along the swing trajectory.
  // A swing leg's row is its same-side neighbour's instead (`neighbour`, standing), when that leg
  // is nearer than the stairs: a hind foot swinging in under its front leg's shank.
  void ClearanceRow(BodyQp::KnotRows& into, int k, int l, double t, const BodyPose& at, const Eigen::Vector4d& v0,
                    const Eigen::Vector4d& motion, const StanceLegRows& rows, bool swing,
                    const StanceLegRows* neighbour = nullptr);
  // Leg l's distance to leg n (rows and rows_n at the pose), linearised in the base frame: both
  // legs' joints turn as the body moves with their feet held. False when farther than the range
  // or when `than` is nearer.
  bool LegPairRow(BodyQp::KnotRows& into, int row, int l, const StanceLegRows& rows, int n, const StanceLegRows& rows_n,
                  const Eigen::Vector4d& v0, const Eigen::Vector4d& motion, double inset, double than);
  // The body's clearance row k of `into` at the pose `at`: its closest point's distance to the
  // stairs (FCL).
  void BodyClearanceRow(BodyQp::KnotRows& into, int k, const BodyPose& at, const Eigen::Vector4d& v0,
                        const Eigen::Vector4d& motion);
  // The body's motion over half of knot interval k0, from v0 at knot k0 to v1 at knot k0 + 1, the
  // neutral stance's advance included, in the QP's variables.
  Eigen::Vector4d HalfKnotMotion(int k0, const Eigen::Vector4d& v0, const Eigen::Vector4d& v1) const;
  // The clearance rows half a knot after each knot (BodyQp::passing), linearised at the mean of
  // the two knots' centres, for the legs (and the body) with a clearance row at either knot;
  // carried across cycles as the knots' rows are (KnotRowCache).
  void PassingRows(double now);
  // Clearance row `row` from the closest pair `c` and the closest robot point moved by a small
  // step along each body variable (`moved`, one column per variable), kept `inset` beyond the
  // clearance margin, and more where the body's `motion` to the next sample (half a knot) sweeps
  // the point past the stairs.
  void SetClearanceRow(BodyQp::KnotRows& into, int row, const Clearance& c, const Eigen::Vector4d& v0,
                       const Eigen::Vector4d& motion, double inset, const Eigen::Matrix<double, 3, 4>& moved);
  // Moves knot k's shift reference to the shift that widens its narrowest stance-leg range.
  void RestoreShift(int k, double neutral_x, double pitch_lo, double pitch_hi, double width);
  // Previous plan's pitch and shift at time t (held beyond its ends).
  double PreviousAt(const Eigen::VectorXd& values, double t) const;
  // With leg rows: the height nearest `start`'s at which every leg stands (see StartState()).
  double StandingHeight(const BodyState& start) const;
  void StoreSolution(const optim::SolveResult& result, double now);
  // Counts the stance legs whose bounds the stored plan breaks (knots 1..), into output_.
  void CountConflicts();
  void ShiftPrevious(double now);
  void FillOutput(double now);

  BodyPlannerSettings settings_;
  FootSchedule schedule_;
  std::shared_ptr<BodyBounds> bounds_;
  std::unique_ptr<BodyQp> qp_;
  // The robot's kinematics and collision model (bounds_; null with given bounds or without
  // settings_.stance_rows: no stance rows),
  // the stance rows' workspace and each (knot, leg)'s last joint angles, the next cycle's IK seed.
  KinematicBodyBounds* robot_ = nullptr;
  std::unique_ptr<RobotWorkspace> stance_ws_;
  std::vector<Eigen::Vector3d> stance_q_;  // k * 4 + leg
  std::unique_ptr<ComModel> com_model_;     // the exact COM (with leg rows only)
  std::unique_ptr<KnotRowCache> row_cache_;  // the last cycle's leg rows (with leg rows only)
  std::array<Eigen::Vector3d, kBodyLegs> hips_B_{};
  std::array<double, kBodyLegs> c_{};
  double hip_height_ = 0.0;
  double travel_ = 1.0;  // +1 where the flight goes along world x, -1 against it
  double stairs_pitch_ = 0.0;  // |pitch| of the flight's slope line

  bool has_previous_ = false;
  double previous_t0_ = 0.0;
  Eigen::VectorXd previous_z_, previous_pitch_, previous_shift_, previous_lateral_;
  ComEstimate com_;
  std::vector<LegPhase> phases_;  // (knots + 1) * 4: each leg at now + k * knot_dt, this cycle
  Eigen::VectorXd neutral_x_, neutral_y_;  // this cycle's neutral body xy per knot
  // This cycle's linearisation points per knot, and the points the relaxation answers to (the
  // previous plan; they differ where a new knot was recentred).
  Eigen::Matrix<double, 4, Eigen::Dynamic> centres_, anchors_;
  // SupportRows' record for ZmpSupportRows: each knot's COM without the weight shifts, and per
  // row its edge's normal, normal . first foot, and side (+1: the COM below the edge, -1: above,
  // 0: free).
  Eigen::Matrix2Xd com_base_;
  Eigen::Matrix2Xd support_normal_;
  Eigen::VectorXd support_edge_;
  std::vector<int> support_side_;
  Eigen::VectorXd leg_lo_, leg_hi_;        // each stance leg's own row bounds, k * 4 + leg
  optim::SolveResult result_;
  optim::ActiveSet previous_active_;  // the stored solution's active set (at previous_t0_)
  BodyPlannerOutput output_;
  double solve_estimate_us_ = 0.0;
  static double kDefaultPullIn();
  double pull_in_ = kDefaultPullIn();  // how far a plan breaking a bound must come back per cycle  // running estimate of a warm solve, for the budget
};

}  // namespace stairplan
