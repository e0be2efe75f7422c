// BodyBounds from the robot itself: IK of the leg (KDL, joint limits) for the reach and FCL
// clearances of the leg's links against the stairs' solids for the collision bound. Both are cached
// on a grid of (hip offset along the heading, pitch) nodes: the reach per leg (it does not depend
// on where the foot stands), the clearance per foothold. A node is computed the first time a
// query touches it and kept, in storage sized when the footholds are set, so queries never
// allocate; PlanBody (or a first pass of the control loop) fills the nodes a traversal needs.
// A query returns the worst case over the nodes around its box, which is conservative as long as
// the bounds vary monotonically between nodes; the margins absorb the rest. With leg rows
// (BodyPlannerSettings::stance_rows, the pipeline's body optimisation) the planner reads none of
// these tables: its rows are the exact kinematics and clearances, linearised each cycle, and the
// re-check uses CheckFeet().
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/collision/stair_collision_model.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/body/body_bounds.h"
#include "stairplan/planning/body/body_planner_settings.h"

namespace stairplan {

/// The exact test of one stance leg: IK onto the contact point and the leg's clearance to the stairs.
struct StanceLegCheck {
  IkResult ik;  ///< IK onto the contact point
  double clearance = 0.0;  ///< smallest leg-link to stair distance [m]
  /// True when IK reached the contact and the leg keeps at least `min_clearance` from the stairs.
  bool ok(double min_clearance) const { return ik.ok() && clearance >= min_clearance; }
};

/// BodyBounds from the robot's kinematics (KDL IK) and collision model (FCL clearances), cached
/// per leg and foothold.
class KinematicBodyBounds final : public BodyBounds {
 public:
  /// Builds the robot's kinematics and collision model and the stairs' solids. The body faces
  /// `facing` (yaw 0 or pi). Throws std::invalid_argument naming the field for bad settings.
  KinematicBodyBounds(const RobotModel& robot, const Staircase& stairs, Facing facing,
                      const BodyPlannerSettings& settings = {});
  /// The same on kinematics built already (copied: building them is the costly part).
  KinematicBodyBounds(const RobotKinematics& kinematics, const Staircase& stairs, Facing facing,
                      const BodyPlannerSettings& settings = {});

  void SetFootholds(const std::vector<Foothold>& footholds) override;
  HeightRange HipHeight(const HipBox& box) override;
  HeightRange ReachHeight(const HipBox& box) override;
  /// The foot radius plus hip_height_fraction of the legs' mean reach within their limits.
  double NominalHipHeight() const override { return nominal_hip_height_; }

  /// IK (as the stance check does it: the foot's sphere resting on the contact point) and the
  /// clearance of leg `leg` with its foot on `contact_W` and the body at `body`. Not per cycle.
  StanceLegCheck CheckLeg(int leg, const Eigen::Vector3d& contact_W, const BodyPose& body);

  /// CheckStance() with these models: the four feet on `contacts_W` (stance or swing), every leg's
  /// IK and clearance to the stairs, the neighbouring legs' clearances and the body's; shape pairs
  /// surely farther apart than `prune_above` go unmeasured (ClearanceOptions::prune_above). Not
  /// per cycle.
  StanceResult CheckFeet(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W, double min_clearance,
                         double prune_above = std::numeric_limits<double>::infinity());

  /// The robot's leg kinematics.
  const RobotKinematics& kinematics() const { return *kinematics_; }
  /// The robot's collision shapes.
  const RobotCollisionModel& collision_model() const { return *collision_; }
  /// The stairs' solids.
  const StairCollisionModel& stair_model() const { return *stairs_; }
  /// Grid nodes computed so far (reach, clearance), for diagnostics.
  int reach_nodes_computed() const { return reach_computed_; }
  /// Grid nodes of the clearance bound computed so far, for diagnostics.
  int clearance_nodes_computed() const { return clearance_computed_; }

 private:
  struct ReachNode {
    float lo = 0.0f, hi = -1.0f;
    bool done = false;
  };
  struct ClearNode {
    float lo = 0.0f;
    bool done = false;
  };
  // IK of leg `leg` with its foot's sphere resting on `contact_W` and the body at `body` (CheckLeg's).
  IkResult StanceIk(int leg, const Eigen::Vector3d& contact_W, const BodyPose& body);
  // The body pose putting leg `leg`'s hip at (dx along the heading, nominal lateral, h above)
  // relative to `contact_W`, pitched by `pitch`.
  BodyPose PoseFor(int leg, const Eigen::Vector3d& contact_W, double dx, double h, double pitch) const;
  // The node at grid (i, j), computed the first time it is asked for (inline: the per-cycle
  // queries nearly always find it done).
  const ReachNode& Reach(int leg, int i, int j) {
    ReachNode& node = reach_[static_cast<std::size_t>(leg)][static_cast<std::size_t>(i * np_ + j)];
    return node.done ? node : FillReach(node, leg, i, j);
  }
  float ClearLow(int foothold, int i, int j) {
    ClearNode& node = clear_[static_cast<std::size_t>(foothold)][static_cast<std::size_t>(i * np_ + j)];
    return node.done ? node.lo : FillClearLow(node, foothold, i, j);
  }
  const ReachNode& FillReach(ReachNode& node, int leg, int i, int j);
  float FillClearLow(ClearNode& node, int foothold, int i, int j);
  // HipHeight and ReachHeight: the nodes' bounds interpolated over the box, with the foothold's
  // clearance or without.
  HeightRange Interpolate(const HipBox& box, bool with_clearance);

  BodyPlannerSettings settings_;
  std::unique_ptr<RobotKinematics> kinematics_;
  std::unique_ptr<RobotCollisionModel> collision_;
  std::unique_ptr<StairCollisionModel> stairs_;
  std::unique_ptr<RobotWorkspace> ws_;
  double yaw_ = 0.0, heading_ = 1.0;
  std::vector<double> lateral_;  // per leg: hip y minus foot y in the heading frame
  double x0_ = 0.0, p0_ = 0.0;   // first grid node
  int nx_ = 0, np_ = 0;
  double h_max_ = 0.0;           // highest hip height searched
  double nominal_hip_height_ = 0.0;
  std::vector<std::vector<ReachNode>> reach_;  // [leg][i * np + j]
  std::vector<Foothold> footholds_;
  std::vector<std::vector<ClearNode>> clear_;  // [foothold][i * np + j]
  int reach_computed_ = 0, clearance_computed_ = 0;
};

}  // namespace stairplan
