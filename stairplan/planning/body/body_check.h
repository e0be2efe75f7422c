// The exact test of a body trajectory: at every sample, with every foot where the schedule puts
// it (on its contact or along its swing), every leg must reach its foot by IK within the joint
// limits, and the body, every leg link and each pair of neighbouring legs must keep at least a
// margin from the stairs and from each other (FCL); where asked, the centre of mass (every link,
// legs by their IK) must stand inside the polygon of the standing feet by a margin, and the body
// never farther back along the travel than a bound behind where it had been. That is the
// validator's stance and stability checks, without its step regions, and the planner's promise of
// progress. PlanBody runs it on the QP's plan (the QP's rows are linearised and cached, its COM is
// an affine estimate, and rows it could not keep are relaxed: this is the independent re-check)
// and the NLP reports against it.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/body/foot_schedule.h"
#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/com_model.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// What CheckBodyTrajectory() found.
struct BodyPlanCheck {
  int samples = 0;              ///< body samples checked (each with the interval before it)
  int instants = 0;             ///< instants checked: the samples and those between them
  /// Legs failing IK, clearances (legs, pairs, body) below the margin, instants whose centre of
  /// mass stands less than the stability margin inside the standing feet, and samples farther
  /// back than the retreat bound.
  int violations = 0;
  /// Smallest leg-to-stairs clearance seen [m] (infinite before any).
  double min_clearance = std::numeric_limits<double>::infinity();
  /// Farthest the body moved back along the travel behind where it had been [m].
  double max_retreat = 0.0;
  /// Smallest margin of the centre of mass inside the standing feet's polygon [m] (infinite
  /// when not checked, or before any instant with three feet down).
  double min_stability_margin = std::numeric_limits<double>::infinity();
  std::string first_violation;  ///< e.g. "t=2.350 s, LF: joint_limits"; empty when none
  /// The first instant of each kind of violation of each part (a leg, a pair, the body), in the
  /// order found; the first is first_violation.
  std::vector<std::string> first_of_each;
  /// first_of_each joined with "; ".
  std::string Summary() const;
  /// True when nothing failed.
  bool ok() const { return violations == 0; }
};

/// What the re-check asks of every instant.
struct BodyCheckMargins {
  double clearance = 0.0;  ///< every leg, pair of legs and the body this far from the stairs and each other [m]
  /// The centre of mass this far inside the polygon of the feet standing, at instants with three
  /// or four down [m]. Negative: not checked (a gait whose balance is dynamic).
  double stability = -1.0;
  /// The body no farther back along the travel (world x, the flight's direction) than this
  /// behind the farthest it has been [m]. Infinite: not checked.
  double retreat = std::numeric_limits<double>::infinity();
};

/// The re-check of one plan's body against its feet (the schedule) with the models of `bounds`.
/// Holds references to both.
class BodyChecker {
 public:
  /// The checker of the body against the feet of `schedule`, with the models of `bounds`.
  BodyChecker(KinematicBodyBounds& bounds, const FootSchedule& schedule, const BodyCheckMargins& margins);

  /// Checks sample i of `body` into `check`, and the motion since sample i - 1 at instants a third
  /// of the interval apart (the body interpolated as BodyPoseAt() does): for a planner that checks
  /// its samples as it makes them, in order (the retreat is measured from the samples before).
  void CheckSample(const std::vector<BodyState>& body, std::size_t i, BodyPlanCheck& check);
  /// Every sample of `body`, and the motion between them.
  BodyPlanCheck CheckTrajectory(const std::vector<BodyState>& body);

 private:
  void CheckAt(double t, const BodyPose& pose, BodyPlanCheck& check);
  void CheckStability(double t, const BodyPose& pose, const StanceResult& stance, const std::array<bool, 4>& down,
                      const std::array<Eigen::Vector3d, 4>& feet, BodyPlanCheck& check);

  KinematicBodyBounds& bounds_;
  const FootSchedule& schedule_;
  BodyCheckMargins margins_;
  ComModel com_;
  RobotWorkspace workspace_;
  double farthest_x_ = -std::numeric_limits<double>::infinity();  // of the samples checked
};

/// BodyChecker(bounds, schedule, margins).CheckTrajectory(body).
BodyPlanCheck CheckBodyTrajectory(KinematicBodyBounds& bounds, const FootSchedule& schedule,
                                  const std::vector<BodyState>& body, const BodyCheckMargins& margins);

}  // namespace stairplan
