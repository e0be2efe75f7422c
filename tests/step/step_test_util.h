// Checks shared by the step planner tests: a plan's footsteps against its map and its legs' reach.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/step/reach_model.h"

namespace stairplan::testing {

/// The body at time t, linearly interpolated between the plan's samples.
inline BodyState BodyAt(const Plan& plan, double t) {
  const auto it = std::lower_bound(plan.body.begin(), plan.body.end(), t, [](const BodyState& b, double v) { return b.t < v; });
  if (it == plan.body.begin()) return plan.body.front();
  if (it == plan.body.end()) return plan.body.back();
  const BodyState& b = *it;
  const BodyState& a = *(it - 1);
  const double u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
  BodyState s = a;
  s.t = t;
  s.x = a.x + u * (b.x - a.x);
  s.y = a.y + u * (b.y - a.y);
  s.z = a.z + u * (b.z - a.z);
  s.pitch = a.pitch + u * (b.pitch - a.pitch);
  return s;
}

inline Eigen::Isometry3d BasePose(const BodyState& b) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(b.yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b.pitch, Eigen::Vector3d::UnitY())).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(b.x, b.y, b.z);
  return pose;
}

/// Hip-to-foot-centre distance over max_reach for footstep f with the plan's body at time t.
inline double Extension(const RobotModel& robot, const Plan& plan, const Footstep& f, double t) {
  const LegModel& leg = robot.leg(f.leg);
  const Eigen::Vector3d centre = f.position_W + Eigen::Vector3d(0.0, 0.0, leg.foot_radius);
  return GeometricReachModel::Extension(leg, BasePose(BodyAt(plan, t)), centre);
}

/// When the foot placed by footstep f lifts off again: the leg's next liftoff, or the plan's end.
inline double LiftoffAfter(const Plan& plan, const Footstep& f) {
  bool seen = false;
  for (const Footstep& g : plan.footsteps) {
    if (&g == &f) {
      seen = true;
    } else if (seen && g.leg == f.leg) {
      return g.t_liftoff;
    }
  }
  return plan.duration();
}

}  // namespace stairplan::testing
