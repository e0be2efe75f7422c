#include "stairplan/planning/body/body_check.h"

#include <algorithm>
#include <cstdio>

#include "stairplan/collision/clearance.h"

namespace stairplan {

void CheckBodySample(KinematicBodyBounds& bounds, const FootSchedule& schedule, const BodyState& b, double min_clearance,
                     BodyPlanCheck& check) {
  ++check.samples;
  BodyPose pose;
  pose.position_W = Eigen::Vector3d(b.x, b.y, b.z);
  pose.pitch = b.pitch;
  pose.yaw = b.yaw;
  ClearanceOptions body_options;
  body_options.prune_above = min_clearance;
  const double body_clearance =
      BodyStairClearance(bounds.collision_model(), bounds.stair_model(), pose, body_options).distance;
  if (!(body_clearance >= min_clearance) && check.violations++ == 0) {
    char text[160];
    std::snprintf(text, sizeof(text), "t=%.3f s, body: clearance below the margin", b.t);
    check.first_violation = text;
  }
  for (int l = 0; l < schedule.leg_count(); ++l) {
    const LegPhase phase = schedule.Phase(l, b.t);
    if (!phase.stance) continue;
    const StanceLegCheck leg = bounds.CheckLeg(l, phase.foot_W, pose);
    if (leg.ik.ok()) check.min_clearance = std::min(check.min_clearance, leg.clearance);
    if (leg.ok(min_clearance)) continue;
    if (check.violations++ == 0) {
      char text[160];
      std::snprintf(text, sizeof(text), "t=%.3f s, %s: %s", b.t, bounds.kinematics().leg(l).name().c_str(),
                    leg.ik.ok() ? "clearance below the margin" : ToString(leg.ik.status));
      check.first_violation = text;
    }
  }
}

BodyPlanCheck CheckBodyTrajectory(KinematicBodyBounds& bounds, const FootSchedule& schedule,
                                  const std::vector<BodyState>& body, double min_clearance) {
  BodyPlanCheck check;
  for (const BodyState& b : body) CheckBodySample(bounds, schedule, b, min_clearance, check);
  return check;
}

}  // namespace stairplan
