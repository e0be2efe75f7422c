#include "stairplan/planning/body/com_estimate.h"

#include "stairplan/kinematics/robot_kinematics.h"
#include "stairplan/planning/com_model.h"

namespace stairplan {

ComEstimate CalibrateComEstimate(const RobotKinematics& kinematics, const std::array<Eigen::Vector3d, 4>& contacts_W,
                                 const BodyState& body) {
  const ComModel com_model(kinematics);
  RobotWorkspace ws(kinematics);
  // The COM with every leg's foot on its contact (through IK) for the body at `b`.
  const auto com = [&](const BodyState& b) {
    BodyPose pose;
    pose.position_W = {b.x, b.y, b.z};
    pose.pitch = b.pitch;
    pose.yaw = b.yaw;
    std::array<Eigen::Vector3d, 4> q;
    for (int l = 0; l < 4; ++l) {
      const Eigen::Vector3d foot =
          contacts_W[static_cast<std::size_t>(l)] + Eigen::Vector3d(0.0, 0.0, kinematics.leg(l).model().foot_radius);
      q[static_cast<std::size_t>(l)] = kinematics.SolveFootIkWorld(l, foot, pose, ws).q;
    }
    return Eigen::Vector2d(com_model.Com(pose, q, ws).head<2>());
  };
  constexpr double kStep = 0.01, kPitchStep = 0.05;  // [m], [rad]: small against the legs' reach
  ComEstimate e;
  const Eigen::Vector2d c0 = com(body);
  BodyState b = body;
  b.x += kStep;
  e.gain.x() = (com(b).x() - c0.x()) / kStep;
  b = body;
  b.y += kStep;
  e.gain.y() = (com(b).y() - c0.y()) / kStep;
  b = body;
  b.pitch += kPitchStep;
  e.pitch_slope = (com(b) - c0) / kPitchStep;
  e.pitch0 = body.pitch;
  e.foot_gain = (Eigen::Vector2d::Ones() - e.gain) / 4.0;
  Eigen::Vector2d feet_sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& c : contacts_W) feet_sum += c.head<2>();
  e.offset = c0 - e.gain.cwiseProduct(Eigen::Vector2d(body.x, body.y)) - e.foot_gain.cwiseProduct(feet_sum);
  return e;
}

}  // namespace stairplan
