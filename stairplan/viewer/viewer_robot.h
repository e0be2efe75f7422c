// The robot as the viewer draws it: the URDF's collision primitives, grouped by leg and body as
// the collision model holds them, posed in the world for a body pose and joint angles. The page
// gets these poses and needs no kinematics of its own.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stairplan/collision/stance_check.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

/// How a shape is drawn; the page has one builder per type (a mesh type joins with mesh robots).
enum class ViewerShapeType { kBox, kCylinder, kSphere };
/// Returns "box", "cylinder" or "sphere", the page's names.
const char* ToString(ViewerShapeType type);

/// One drawable shape fixed to a link.
struct ViewerShape {
  ViewerShapeType type = ViewerShapeType::kBox;  ///< box, cylinder or sphere
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box sides; cylinder (r, r, length); sphere (r, r, r) [m]
  std::string link;  ///< the URDF link it belongs to
  std::string group;   ///< the leg ("LF".."RH") or "body"
  int leg = -1;        ///< RobotKinematics leg index, -1 for the body
  int segment = -1;    ///< that leg's link frame carrying it, -1: the base frame
  Eigen::Isometry3d local = Eigen::Isometry3d::Identity();  ///< pose in its frame
};

/// Joint angles of the four legs, in RobotKinematics leg order [rad].
using LegAngles = std::array<Eigen::Vector3d, 4>;

/// Built once per robot and staircase. Not thread-safe (one workspace).
class ViewerRobot {
 public:
  /// Throws std::invalid_argument naming the link for geometry it cannot draw (meshes, for now).
  ViewerRobot(const RobotModel& robot, const Staircase& stairs);

  /// Every drawable shape of the robot.
  const std::vector<ViewerShape>& shapes() const { return shapes_; }
  /// The robot's kinematics.
  const RobotKinematics& kinematics() const { return checker_.kinematics(); }

  /// The joint angles of a plan instant, found as the validator finds them: each foot's sphere on
  /// its contact point (legs in kinematics order), IK from the leg's nominal posture.
  LegAngles PlanAngles(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W);
  /// Every shape's pose in the world, in shapes() order.
  void ShapePoses(const BodyPose& body, const LegAngles& q, std::vector<Eigen::Isometry3d>* poses_W);

 private:
  StanceChecker checker_;
  std::vector<ViewerShape> shapes_;
};

}  // namespace stairplan
