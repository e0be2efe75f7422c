#include "stairplan/planning/body_path.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <urdf_model/model.h>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/com_model.h"
#include "stairplan/planning/posture_fit.h"

namespace stairplan {
namespace {

struct Keyframe {
  double t;
  Eigen::Vector2d com_xy;
};

Eigen::Vector2d Centroid(const std::vector<Eigen::Vector3d>& feet, const std::vector<bool>& use) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (std::size_t i = 0; i < feet.size(); ++i) {
    if (!use[i]) continue;
    sum += feet[i].head<2>();
    ++n;
  }
  return n > 0 ? Eigen::Vector2d(sum / n) : sum;
}

// COM keyframes: at the start and end the centroid of all four feet; through each swing the
// centroid of the other three (blended by `shift` toward the four-foot centroid).
std::vector<Keyframe> ComKeyframes(const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& initial,
                                   const std::vector<Footstep>& steps, double shift) {
  const std::vector<bool> all(legs.size(), true);
  std::vector<Keyframe> keys = {{0.0, Centroid(initial, all)}};
  for (const Footstep& s : steps) {
    const double mid = 0.5 * (s.t_liftoff + s.t_touchdown);
    std::vector<bool> stance;
    const std::vector<Eigen::Vector3d> feet = FeetAt(legs, initial, steps, mid, &stance);
    const Eigen::Vector2d target = shift * Centroid(feet, stance) + (1.0 - shift) * Centroid(feet, all);
    keys.push_back({s.t_liftoff, target});
    keys.push_back({s.t_touchdown, target});
  }
  const double end = steps.empty() ? 0.0 : steps.back().t_touchdown;
  keys.push_back({end + 1e-9, Centroid(FeetAt(legs, initial, steps, end + 1.0), all)});
  return keys;
}

Eigen::Vector2d ComAt(const std::vector<Keyframe>& keys, double t) {
  const auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const Keyframe& k) { return v < k.t; });
  if (next == keys.begin()) return keys.front().com_xy;
  if (next == keys.end()) return keys.back().com_xy;
  const Keyframe& a = *(next - 1);
  const double u = next->t > a.t ? (t - a.t) / (next->t - a.t) : 1.0;
  return a.com_xy + SmoothStep(u) * (next->com_xy - a.com_xy);
}

// Moves the body horizontally until the COM of the posture (legs through IK) is at `target`.
void CorrectCom(const RobotKinematics& kinematics, const ComModel& com_model, RobotWorkspace& ws,
                const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& feet,
                const Eigen::Vector2d& target, int passes, BodyState& b) {
  for (int pass = 0; pass < passes; ++pass) {
    BodyPose pose;
    pose.position_W = {b.x, b.y, b.z};
    pose.pitch = b.pitch;
    pose.yaw = b.yaw;
    std::array<Eigen::Vector3d, 4> q;
    for (std::size_t i = 0; i < legs.size() && i < 4; ++i) {
      const int l = kinematics.LegIndex(legs[i]);
      const Eigen::Vector3d foot = feet[i] + Eigen::Vector3d(0.0, 0.0, kinematics.leg(l).model().foot_radius);
      q[static_cast<std::size_t>(l)] = kinematics.SolveFootIkWorld(l, foot, pose, ws).q;
    }
    const Eigen::Vector3d com = com_model.Com(pose, q, ws);
    b.x -= com.x() - target.x();
    b.y -= com.y() - target.y();
  }
}

}  // namespace

void BodyPathSettings::Validate() const {
  RequireInRange("hip_height_fraction", hip_height_fraction, 0.05, 1.0);
  RequireInRange("sample_period", sample_period, 1e-3, 1.0);
  RequireInRange("stability_shift", stability_shift, 0.0, 1.0);
  RequireInRange("pitch_fraction", pitch_fraction, 0.0, 1.0);
  RequireInRange("touchdown_clearance", touchdown_clearance, -1.0, 0.1);
  RequireInRange("height_margin", height_margin, 0.0, 0.1);
  RequireInRange("height_centering", height_centering, 0.0, 0.5);
  RequireInRange("height_key_period", height_key_period, 0.01, 10.0);
  RequireInRange("wide_height_range", wide_height_range, 0.0, 1.0);
  RequireInRange("max_shift", max_shift, 0.0, 0.5);
  RequireInRange("shift_step", shift_step, 0.005, 0.5);
  RequireInRange("shift_margin", shift_margin, 0.0, 0.5);
  RequireInRange("max_height_acceleration", max_height_acceleration, 0.1, 100.0);
  swing.Validate();
  if (com_passes < 0 || com_passes > 10) throw FieldError("com_passes", "must be from 0 to 10");
}

std::vector<BodyState> BodyPathForFootsteps(const RobotModel& robot, const std::vector<std::string>& legs,
                                            const std::vector<Eigen::Vector3d>& initial_feet,
                                            const std::vector<Footstep>& footsteps, double yaw,
                                            const BodyPathSettings& settings, const Staircase* stairs) {
  settings.Validate();
  const RobotKinematics kinematics(robot);
  const ComModel com_model(kinematics);
  RobotWorkspace ws(kinematics);
  double reach = 0.0, hip_z = 0.0, foot_radius = 0.0;
  for (const LegKinematics& leg : kinematics.legs()) {
    reach += leg.reach().hi / 4.0;  // the reach the joint limits allow, not the sum of the links
    hip_z += leg.hip_B().z() / 4.0;
    foot_radius += leg.model().foot_radius / 4.0;
  }
  const double hip_height = settings.hip_height_fraction * reach;
  const Eigen::Vector3d com_B = ApproximateComOffset(robot);
  const Eigen::Vector2d com_offset_W = Eigen::Rotation2Dd(yaw) * com_B.head<2>();
  const std::vector<Keyframe> keys = ComKeyframes(legs, initial_feet, footsteps, settings.stability_shift);
  const double duration = footsteps.empty() ? 0.0 : footsteps.back().t_touchdown;
  const int samples = static_cast<int>(std::ceil(duration / settings.sample_period - 1e-9));
  std::vector<BodyState> body;
  for (int s = 0; s <= samples; ++s) {
    const double t = std::min(duration, s * settings.sample_period);
    const std::vector<Eigen::Vector3d> feet = FeetAt(legs, initial_feet, footsteps, t);
    double sum_z = 0.0, front_x = 0.0, front_z = 0.0, hind_x = 0.0, hind_z = 0.0;
    Eigen::Vector2d feet_xy = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < feet.size(); ++i) {
      sum_z += feet[i].z() / 4.0;
      feet_xy += feet[i].head<2>() / 4.0;
      const bool front = robot.leg(legs[i]).hip_B.x() > 0.0;
      (front ? front_x : hind_x) += feet[i].x() / 2.0;
      (front ? front_z : hind_z) += feet[i].z() / 2.0;
    }
    BodyState b;
    b.t = t;
    const Eigen::Vector2d com = ComAt(keys, t);
    b.x = com.x() - com_offset_W.x();
    b.y = com.y() - com_offset_W.y();
    b.z = sum_z + foot_radius + hip_height - hip_z;
    b.yaw = yaw;
    b.pitch = -settings.pitch_fraction * std::atan2(front_z - hind_z, (front_x - hind_x) * std::cos(yaw));
    b.com_shift = (com - feet_xy).dot(Eigen::Vector2d(std::cos(yaw), std::sin(yaw)));
    CorrectCom(kinematics, com_model, ws, legs, feet, com, settings.com_passes, b);
    body.push_back(b);
  }
  if (stairs != nullptr && settings.touchdown_clearance >= 0.0) {
    const auto com_target = [&keys](double t) { return ComAt(keys, t); };
    FitPosturesToStances(robot, *stairs, legs, initial_feet, footsteps, com_target, settings, body);
  }
  return body;
}

}  // namespace stairplan
