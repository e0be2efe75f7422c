#include "stairplan/kinematics/robot_kinematics.h"

#include <cmath>
#include <stdexcept>

#include "stairplan/kinematics/urdf_to_kdl.h"

namespace stairplan {

RobotKinematics::RobotKinematics(const RobotModel& robot)
    : robot_(robot), tree_(std::make_shared<KDL::Tree>(UrdfToKdlTree(robot.urdf()))) {
  for (const LegModel& leg : robot_.legs()) legs_.emplace_back(leg, *tree_, robot_.base_link());
}

int RobotKinematics::LegIndex(const std::string& name) const {
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    if (legs_[i].name() == name) return static_cast<int>(i);
  }
  throw std::invalid_argument("RobotKinematics: no leg named '" + name + "'");
}

const LegKinematics& RobotKinematics::leg(const std::string& name) const { return legs_[static_cast<std::size_t>(LegIndex(name))]; }

IkResult RobotKinematics::SolveFootIkWorld(int index, const Eigen::Vector3d& foot_W, const BodyPose& body,
                                           RobotWorkspace& ws, const IkSettings& settings) const {
  const Eigen::Vector3d foot_B = body.ToIsometry().inverse() * foot_W;
  return leg(index).SolveFootIk(foot_B, ws.leg(index), settings);
}

Interval1 RobotKinematics::ReachableBodyHeights(int index, const Eigen::Vector3d& foot_W, const BodyPose& body,
                                                RobotWorkspace& ws, double step, double tolerance) const {
  if (!(step > 0.0) || !(tolerance > 0.0)) {
    throw std::invalid_argument("RobotKinematics::ReachableBodyHeights: step and tolerance must be positive");
  }
  const LegKinematics& l = leg(index);
  IkSettings settings;
  settings.tolerance = 1e-7;
  BodyPose probe = body;
  const auto reachable = [&](double z) {
    probe.position_W.z() = z;
    return SolveFootIkWorld(index, foot_W, probe, ws, settings).ok();
  };
  // The hip can be at most the leg's reach above or below the foot; the hip's offset from the
  // base origin widens the window.
  const double span = l.reach().hi + l.hip_B().norm();
  const double z_lo = foot_W.z() - span, z_hi = foot_W.z() + span;
  // The reachable heights nearest to the middle of the longest reachable run found by the scan.
  double run_lo = 0.0, run_hi = -1.0, best_lo = 0.0, best_hi = -1.0;
  bool in_run = false;
  for (double z = z_lo; z <= z_hi + 1e-12; z += step) {
    if (reachable(z)) {
      if (!in_run) run_lo = z;
      run_hi = z;
      in_run = true;
      if (run_hi - run_lo > best_hi - best_lo) {
        best_lo = run_lo;
        best_hi = run_hi;
      }
    } else {
      in_run = false;
    }
  }
  Interval1 result;
  if (best_hi < best_lo) return result;
  // Bisection between the last unreachable and the first reachable sample on each side.
  double out = best_lo - step, in = best_lo;
  while (in - out > tolerance) {
    const double mid = 0.5 * (in + out);
    (reachable(mid) ? in : out) = mid;
  }
  result.lo = in;
  out = best_hi + step;
  in = best_hi;
  while (out - in > tolerance) {
    const double mid = 0.5 * (in + out);
    (reachable(mid) ? in : out) = mid;
  }
  result.hi = in;
  return result;
}

RobotWorkspace::RobotWorkspace(const RobotKinematics& kinematics) {
  for (const LegKinematics& leg : kinematics.legs()) legs_.emplace_back(leg);
}

}  // namespace stairplan
