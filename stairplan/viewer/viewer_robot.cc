#include "stairplan/viewer/viewer_robot.h"

namespace stairplan {
namespace {

ViewerShapeType DrawnType(ShapeType type) {
  switch (type) {
    case ShapeType::kBox: return ViewerShapeType::kBox;
    case ShapeType::kCylinder: return ViewerShapeType::kCylinder;
    case ShapeType::kSphere: return ViewerShapeType::kSphere;
    // A mesh is drawn as its bounding box (CollisionShape::size and local hold it) until the page
    // draws meshes.
    case ShapeType::kMesh: return ViewerShapeType::kBox;
  }
  return ViewerShapeType::kBox;
}

ViewerShape Drawn(const CollisionShape& shape, const std::string& group, int leg) {
  ViewerShape s;
  s.type = DrawnType(shape.type);
  s.size = shape.size;
  s.link = shape.link;
  s.group = group;
  s.leg = leg;
  s.segment = shape.segment;
  s.local = shape.local;
  return s;
}

}  // namespace

const char* ToString(ViewerShapeType type) {
  switch (type) {
    case ViewerShapeType::kBox: return "box";
    case ViewerShapeType::kCylinder: return "cylinder";
    case ViewerShapeType::kSphere: return "sphere";
  }
  return "box";
}

ViewerRobot::ViewerRobot(const RobotModel& robot, const Staircase& stairs) : checker_(robot, stairs) {
  const RobotCollisionModel& collision = checker_.collision_model();
  for (const CollisionShape& shape : collision.body_shapes()) shapes_.push_back(Drawn(shape, "body", -1));
  for (int l = 0; l < collision.leg_count(); ++l) {
    for (const CollisionShape& shape : collision.leg_shapes(l)) {
      shapes_.push_back(Drawn(shape, kinematics().leg(l).name(), l));
    }
  }
}

LegAngles ViewerRobot::PlanAngles(const BodyPose& body, const std::array<Eigen::Vector3d, 4>& contacts_W) {
  const StanceResult stance = checker_.Check(body, contacts_W);
  LegAngles q;
  for (std::size_t l = 0; l < q.size(); ++l) q[l] = stance.legs[l].ik.q;
  return q;
}

void ViewerRobot::ShapePoses(const BodyPose& body, const LegAngles& q, std::vector<Eigen::Isometry3d>* poses_W) {
  const Eigen::Isometry3d base_W = body.ToIsometry();
  std::array<std::vector<Eigen::Isometry3d>, 4> frames_B;
  for (int l = 0; l < kinematics().leg_count() && l < 4; ++l) {
    const auto i = static_cast<std::size_t>(l);
    frames_B[i] = kinematics().leg(l).LinkFrames(q[i], checker_.workspace().leg(l));
  }
  poses_W->clear();
  for (const ViewerShape& s : shapes_) {
    if (s.leg < 0 || s.segment < 0) {
      poses_W->push_back(base_W * s.local);
    } else {
      const auto& frames = frames_B[static_cast<std::size_t>(s.leg)];
      poses_W->push_back(base_W * frames.at(static_cast<std::size_t>(s.segment)) * s.local);
    }
  }
}

}  // namespace stairplan
