// The exact test of a body trajectory: at every sample, with every foot where the schedule puts
// it (on its contact or along its swing), every leg must reach its foot by IK within the joint
// limits, and the body, every leg link and each pair of neighbouring legs must keep at least a
// margin from the stairs and from each other (FCL): the validator's stance checks, without its
// stability and step regions. PlanBody runs it on the QP's plan (the QP's rows are linearised
// and cached; this is the independent re-check) and the NLP reports against it.
#pragma once

#include <limits>
#include <string>

#include "stairplan/planning/body/kinematic_body_bounds.h"
#include "stairplan/planning/body/foot_schedule.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// What CheckBodyTrajectory() found.
struct BodyPlanCheck {
  int samples = 0;              ///< body samples checked (each with the interval before it)
  int instants = 0;             ///< instants checked: the samples and those between them
  int violations = 0;           ///< legs failing IK, and clearances (legs, pairs, body) below the margin
  /// Smallest leg-to-stairs clearance seen [m] (infinite before any).
  double min_clearance = std::numeric_limits<double>::infinity();
  std::string first_violation;  ///< e.g. "t=2.350 s, LF: joint_limits"; empty when none
  /// True when nothing failed.
  bool ok() const { return violations == 0; }
};

/// Checks sample i of `body` into `check`, and the motion since sample i - 1 at instants a third
/// of the interval apart (the body interpolated as BodyPoseAt() does), as CheckBodyTrajectory()
/// checks each sample: for a planner that checks its samples as it makes them.
void CheckBodySample(KinematicBodyBounds& bounds, const FootSchedule& schedule, const std::vector<BodyState>& body,
                     std::size_t i, double min_clearance, BodyPlanCheck& check);

/// Checks every sample of `body`, and the motion between them, against the feet of `schedule`
/// with the models in `bounds`.
BodyPlanCheck CheckBodyTrajectory(KinematicBodyBounds& bounds, const FootSchedule& schedule,
                                  const std::vector<BodyState>& body, double min_clearance);

}  // namespace stairplan
