// The step planner (US 2020/0324412 A1 ("Robotically negotiating stairs") [0033]-[0035], [0070],
// claims 9-12): a set of fixed-cadence controllers (swing duration x gait) each turns the body's
// velocity command into an unconstrained step plan over a horizon; every cycle each plan is checked
// against hard rules (a target no leg reaches, a step too high to clear), scored against the
// constrained map (distance of each unconstrained footstep from the nearest step region dominates;
// soft terms for swing height, reach and timing), and the lowest score wins. The chosen plan's
// targets are snapped into their step regions; a leading leg never lands behind its trailing leg,
// and a trailing leg passes its leading leg only at a cost, when nothing else is in reach ([0070]).
//
// Built once from the robot, the map and the settings; Update() allocates nothing.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/step/gait_pattern.h"
#include "stairplan/planning/step/ground_profile.h"
#include "stairplan/planning/step/reach_model.h"
#include "stairplan/planning/step/step_planner_settings.h"

namespace stairplan {

/// One controller: a fixed swing duration with a gait.
struct FixedCadenceController {
  double cadence_s = 0.0;  ///< swing duration [s]
  Gait gait = Gait::kCrawl;  ///< which legs swing together, in which order
};

/// A leg as the planner sees it at the start of a cycle.
struct StepLegState {
  Eigen::Vector3d foot_W = Eigen::Vector3d::Zero();  ///< contact point [m]
  int stair = -1;                 ///< the surface it stands on, -1 when unknown
  double last_touchdown_s = 0.0;  ///< when it last landed [s]; the longest-standing leg swings first
};

/// The per-cycle input: where the body is, where it is told to go, where the feet are.
struct StepPlannerInput {
  double now_s = 0.0;  ///< the cycle's time [s]
  Eigen::Vector2d body_xy_W = Eigen::Vector2d::Zero();   ///< base origin, horizontal [m]
  Eigen::Vector2d velocity_W = Eigen::Vector2d::Zero();  ///< commanded body velocity [m/s]
  std::array<StepLegState, 4> legs{};                    ///< in the robot's leg order
};

/// Why a controller was ruled out before scoring.
enum class RuleOut {
  kNone,
  kNoStepRegion,    ///< the map has no step region near a footstep
  kStepTooHigh,     ///< a footstep needs a step higher than the leg can clear
  kUnreachable,     ///< no target in reach from touchdown through the longest coming stance
  kStanceLost,      ///< a stance foot falls out of reach before the plan lifts it
  kLeaderBehind,    ///< the only targets land a leading leg behind its trailing leg (US 2020/0324412 [0070])
  kStepsBack,       ///< the only targets lie on a stair behind the leg's own
};
/// Returns the reason in words, e.g. "no step region".
const char* ToString(RuleOut reason);

/// One footstep of a controller's plan, unconstrained and snapped.
struct PlannedStep {
  int leg = -1;                 ///< index into the robot's legs
  double t_liftoff = 0.0;  ///< when the foot leaves `from_W` [s]
  double t_touchdown = 0.0;  ///< when it lands on `target_W` [s]
  Eigen::Vector2d unconstrained_xy_W = Eigen::Vector2d::Zero();  ///< where the cadence puts the foot
  double region_distance = 0.0; ///< from there to the nearest step region [m]
  int nearest_stair = -1;  ///< the stair of that nearest step region
  Eigen::Vector3d from_W = Eigen::Vector3d::Zero();  ///< the foothold it leaves [m]
  int from_stair = -1;  ///< the stair of that foothold
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< snapped contact point in its step region
  int target_stair = -1;  ///< the stair of the target
  RuleOut rule_out = RuleOut::kNone;  ///< set on the footstep that ruled the controller out
};

/// One controller's result in the latest cycle.
struct ControllerEvaluation {
  bool admissible = false;  ///< no hard rule ruled it out
  double score = std::numeric_limits<double>::infinity();  ///< total, switch cost included
  RuleOut rule_out = RuleOut::kNone;  ///< the rule that ruled it out, kNone when admissible
  int rule_out_step = -1;       ///< the footstep that broke the rule
  double rule_out_value = 0.0;  ///< the offending quantity (step height [m], reach fraction)
  ///@{
  /// The score's terms: step-region distance, snapping, trailing legs, swing height, reach, timing,
  /// switching.
  double region_cost = 0.0, snap_cost = 0.0, trailing_cost = 0.0, swing_height_cost = 0.0, reach_cost = 0.0, timing_cost = 0.0,
         switch_cost = 0.0;
  ///@}
  int step_count = 0;               ///< footsteps filled in `steps`
  std::vector<PlannedStep> steps;   ///< sized to the horizon at construction
};

/// The fixed-cadence step planner of a control loop (see the file's top comment).
class StepPlanner {
 public:
  /// Throws std::invalid_argument naming the field for bad settings, an empty map or a robot whose
  /// legs are not one per corner. `reach` defaults to the GeometricReachModel of the settings.
  StepPlanner(const RobotModel& robot, const ConstrainedMap& map, const StepPlannerSettings& settings = {},
              std::shared_ptr<const ReachModel> reach = nullptr);

  /// One cycle: evaluates every controller from `input`, selects the lowest score (ties: the
  /// current controller, then the lowest index) and returns its index, or -1 when none is
  /// admissible (the evaluations say why). Allocation-free; throws std::invalid_argument on
  /// non-finite input.
  int Update(const StepPlannerInput& input);

  /// The selected controller, -1 before the first Update or when none was admissible.
  int selected() const { return selected_; }
  /// Every controller: each cadence with each gait.
  const std::vector<FixedCadenceController>& controllers() const { return controllers_; }
  /// Every controller's evaluation in the latest cycle, in controllers() order.
  const std::vector<ControllerEvaluation>& evaluations() const { return evaluations_; }
  /// Controller `index`'s evaluation; throws std::invalid_argument for a bad index.
  const ControllerEvaluation& evaluation(int index) const;
  /// Why controller `index` was ruled out in the latest cycle, "" when it was not (allocates).
  std::string RuleOutReason(int index) const;
  /// Forgets the current controller (no hysteresis on the next Update).
  void Reset() { selected_ = -1; }

  /// The base pose the plans assume with the base origin above `body_xy_W`: hip height above the
  /// stairs' pitch line, pitched along it, yawed to the map's facing.
  Eigen::Isometry3d BodyPoseAt(const Eigen::Vector2d& body_xy_W) const;
  /// Its pitch (nose-up negative, as in BodyState) [rad].
  double BodyPitchAt(const Eigen::Vector2d& body_xy_W) const;
  /// The body's heading for the map's facing [rad].
  double yaw() const { return yaw_; }
  /// Hip height above the pitch line [m].
  double hip_height() const { return hip_height_; }
  /// Where `leg` stands with the body at body_xy_W, before snapping (horizontal) [m].
  Eigen::Vector2d NeutralFootXY(int leg, const Eigen::Vector2d& body_xy_W) const;
  /// The leg in `role` for the map's facing.
  int LegOfRole(TravelRole role) const { return leg_of_role_[static_cast<std::size_t>(role)]; }
  /// The robot's legs.
  const std::vector<LegModel>& legs() const { return legs_; }
  /// The map planned on.
  const ConstrainedMap& map() const { return map_; }
  /// The settings it was built with.
  const StepPlannerSettings& settings() const { return settings_; }
  /// How reach is judged.
  const ReachModel& reach_model() const { return *reach_; }
  /// The target the planner would choose for a foot at p on stair `stair`, margin applied.
  Eigen::Vector2d SnapIntoRegion(int stair, const Eigen::Vector2d& p) const;
  /// Nearest stair with a step region to p (by planar distance), -1 when none; allocation-free.
  int NearestRegion(const Eigen::Vector2d& p, double* distance) const;

 private:
  struct RegionInfo {
    bool present = false;
    bool rectangle = false;
    double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;          // bounding box
    double in_x_lo = 0.0, in_x_hi = 0.0, in_y_lo = 0.0, in_y_hi = 0.0;  // inset by the margin
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    double z = 0.0;
  };

  void Evaluate(int index, const StepPlannerInput& input);
  // Planar distance from p to the step region of stair k (which must have one).
  double RegionDistance(int k, const Eigen::Vector2d& p) const;

  std::vector<LegModel> legs_;
  ConstrainedMap map_;
  StepPlannerSettings settings_;
  std::shared_ptr<const ReachModel> reach_;
  GroundProfile ground_;
  std::vector<RegionInfo> regions_;
  std::vector<double> surface_x_end_;
  std::vector<FixedCadenceController> controllers_;
  std::vector<ControllerEvaluation> evaluations_;
  // Update's workspace: base poses per cadence at liftoffs/touchdowns and at the ends of stances.
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> poses_;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> end_poses_;
  double longest_stance_s_ = 0.0;  // the longest stance any controller gives a leg [s]
  std::size_t pose_stride_ = 0;    // poses per cadence in poses_
  std::array<int, 4> leg_of_role_{};
  std::array<int, 4> role_of_leg_{};
  std::array<Eigen::Vector2d, 4> neutral_offset_W_{};  // foot under the hip, stance width, yawed
  std::array<double, 4> max_step_height_{};
  double yaw_ = 0.0;
  double cos_yaw_ = 1.0;
  double sin_yaw_ = 0.0;
  double hip_height_ = 0.0;
  double mean_hip_z_ = 0.0;
  double mean_foot_radius_ = 0.0;
  double fore_hip_x_B_ = 0.0;
  double hind_hip_x_B_ = 0.0;
  int selected_ = -1;
};

}  // namespace stairplan
