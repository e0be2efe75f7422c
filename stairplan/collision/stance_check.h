// Is a stance feasible? For a body pose and four foot contact points: IK of every foot within
// the joint limits, and every leg's clearance to the stairs (and between neighbouring legs).
// This is what the planners and the validator ask at every touchdown.
#pragma once

#include <array>

#include "stairplan/collision/clearance.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_kinematics.h"

namespace stairplan {

/// What a stance needs to pass.
struct StanceSettings {
  IkSettings ik;                ///< IK of each foot (from the leg's nominal seed)
  double min_clearance = 0.0;   ///< every leg link must be farther than this from the stairs [m]
  bool check_contralateral = true;  ///< also LF-RF and LH-RH clearances
  /// Also LF-LH and RF-RH clearances: on a tread shorter than the body, a hind foot can land where
  /// its front foot still stands.
  bool check_ipsilateral = true;
  /// Return at the first failing leg or pair (searches that need only the verdict); the figures
  /// of the legs not reached are then left at their defaults.
  bool stop_at_first_failure = false;
  ClearanceOptions clearance;  ///< how leg-to-stairs clearances are computed

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// How a stance check ended: the first failure found.
enum class StanceStatus {
  kOk,
  kOutOfReach,   ///< some foot cannot be reached
  kJointLimits,  ///< some foot is reachable only beyond a joint limit
  kCollision,    ///< a leg (or the body) is within min_clearance of the stairs, or of another leg
};
/// Returns "ok", "out_of_reach", "joint_limits" or "collision".
const char* ToString(StanceStatus status);

/// One leg's part of the answer.
struct LegStance {
  IkResult ik;           ///< joint angles (within limits) and the IK status
  Clearance stairs;      ///< this leg's clearance to the stairs
};

/// The answer: per leg IK and clearances, the worst figures and an overall status.
struct StanceResult {
  StanceStatus status = StanceStatus::kOk;  ///< the first failure found, or kOk
  std::array<LegStance, 4> legs;   ///< in RobotKinematics leg order
  double min_clearance = 0.0;      ///< smallest leg-to-stairs clearance [m]
  int worst_leg = -1;              ///< the leg with that clearance
  Clearance front_pair;            ///< LF-RF (legs 0, 1) when checked
  Clearance hind_pair;             ///< LH-RH (legs 2, 3) when checked
  Clearance left_pair;             ///< LF-LH (legs 0, 2) when checked
  Clearance right_pair;            ///< RF-RH (legs 1, 3) when checked
  Clearance body;                  ///< the body's shapes to the stairs
  /// True when every check passed.
  bool ok() const { return status == StanceStatus::kOk; }
};

/// Checks a stance. `contacts_W` are the feet's contact points on the surface (as in Footstep),
/// in leg order; each foot's sphere is placed on its contact point (centre one radius above).
/// Allocation-free once `ws` exists (FCL allocates only when some pair penetrates).
StanceResult CheckStance(const RobotKinematics& kinematics, const RobotCollisionModel& robot,
                         const StairCollisionModel& stairs, const BodyPose& body,
                         const std::array<Eigen::Vector3d, 4>& contacts_W, RobotWorkspace& ws,
                         const StanceSettings& settings = {});

/// Everything a planner needs to check stances on one staircase, built once: the robot's
/// kinematics, its collision model, the stairs' solids and a workspace. Not thread-safe (one
/// workspace); make one per thread.
class StanceChecker {
 public:
  /// Builds the kinematics, collision models and workspace of `robot` on `stairs` once.
  StanceChecker(const RobotModel& robot, const Staircase& stairs, const StanceSettings& settings = {});
  /// The same on kinematics built already (copied: building them is the costly part).
  StanceChecker(const RobotKinematics& kinematics, const Staircase& stairs, const StanceSettings& settings = {});

  /// CheckStance with this checker's models and settings.
  StanceResult Check(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W);
  /// The same with shape pairs surely farther apart than `prune_above` left unmeasured (as
  /// ClearanceOptions::prune_above; their clearances read infinite): for a judge that keeps only
  /// clearances below a margin and the smallest so far. Above the settings' min_clearance the
  /// status is the full check's.
  StanceResult Check(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W, double prune_above);

  /// The body heights (body.position_W.z, the rest of `body` fixed) at which Check() passes: the
  /// longest passing run found scanning [z_lo, z_hi] in `step`, its ends refined by bisection to
  /// `tolerance`. Empty when no height passes. A planner picks its height inside (e.g. the middle).
  Interval1 FeasibleBodyHeights(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W, double z_lo,
                                double z_hi, double step = 0.01, double tolerance = 1e-3);

  /// The robot's kinematics.
  const RobotKinematics& kinematics() const { return kinematics_; }
  /// The robot's collision shapes.
  const RobotCollisionModel& collision_model() const { return collision_; }
  /// The stairs' solids.
  const StairCollisionModel& stairs() const { return stairs_; }
  /// The workspace Check() uses; callers may use it for their own FK and IK between checks.
  RobotWorkspace& workspace() { return ws_; }

 private:
  RobotKinematics kinematics_;
  RobotCollisionModel collision_;
  StairCollisionModel stairs_;
  StanceSettings settings_;
  StanceSettings verdict_settings_;  ///< settings_ stopping at the first failure (height searches)
  RobotWorkspace ws_;
};

/// The pruning bound (StanceChecker::Check, ClearanceOptions::prune_above) for a judge that keeps
/// only clearances below `margin` and the smallest so far, `smallest`: a little above both, so that
/// a pair exactly at either is still measured and everything it keeps stays exact.
double JudgePruneBound(double smallest, double margin);

/// Whether leg `leg`'s clearance `stairs` (from CheckStance or LegStairClearance) is its foot
/// grazing a tread, up to 0.1 mm deep: a foot lifting off or touching down touches its tread by
/// design, so only deeper penetration counts against a plan.
bool FootGrazesTread(const RobotCollisionModel& robot, int leg, const Clearance& stairs);

/// Where the foot link origin must be for the foot's sphere to rest on `contact_W`, given the
/// foot's orientation in the world (the sphere centre may be offset from the link origin).
Eigen::Vector3d FootOriginForContact(const LegModel& leg, const Eigen::Vector3d& contact_W,
                                     const Eigen::Matrix3d& foot_rotation_W);

/// A body pose with the contacts its feet make standing level in their nominal joint angles.
struct NominalStance {
  BodyPose body;  ///< the base, level, at the nominal height
  std::array<Eigen::Vector3d, 4> contacts_W;  ///< contact points, in leg order [m]
};
/// The robot standing level in its nominal joint angles, its base at x along the stairs and
/// LF's contact (the bottom of its foot sphere, or a mesh foot's contact sphere) at height 0.
NominalStance NominalStanceAt(const RobotKinematics& kinematics, RobotWorkspace& ws, double x);

/// IK of `leg` for its foot to rest on `contact_W` with the body at `body_W`: solved with the
/// foot turned as the body, then (when the contact is offset from the foot origin) re-aimed three
/// times with the foot's orientation from the previous solution, from `seed`.
IkResult SolveContactIk(const LegKinematics& leg, const Eigen::Vector3d& contact_W, const Eigen::Isometry3d& body_W,
                        const Eigen::Vector3d& seed, LegWorkspace& ws, const IkSettings& settings = {});

}  // namespace stairplan
