#include "stairplan/collision/robot_collision_model.h"

#include <map>
#include <stdexcept>

#include <urdf_model/model.h>

#include "stairplan/kinematics/urdf_pose.h"

namespace stairplan {
namespace {

struct Attachment {
  int leg = -1;      // -1: the body
  int segment = -1;  // within the leg's chain
  Eigen::Isometry3d link_in_frame = Eigen::Isometry3d::Identity();
  bool found = false;
};

}  // namespace

RobotCollisionModel::RobotCollisionModel(const RobotKinematics& kinematics) {
  const RobotModel& robot = kinematics.robot();
  const urdf::ModelInterface& urdf = robot.urdf();
  legs_.resize(static_cast<std::size_t>(kinematics.leg_count()));
  foot_shapes_.assign(static_cast<std::size_t>(kinematics.leg_count()), -1);

  // Which frame carries each chain link.
  std::map<std::string, Attachment> frames;
  for (int l = 0; l < kinematics.leg_count(); ++l) {
    const LegKinematics& leg = kinematics.leg(l);
    for (int s = 0; s < leg.segment_count(); ++s) frames[leg.segment_link(s)] = {l, s, Eigen::Isometry3d::Identity(), true};
  }
  frames[robot.base_link()] = {-1, -1, Eigen::Isometry3d::Identity(), true};
  // Links above the base by fixed joints (Unitree's inertia-less root `base` above `trunk`).
  {
    Eigen::Isometry3d base_in_link = Eigen::Isometry3d::Identity();
    for (urdf::LinkConstSharedPtr link = urdf.getLink(robot.base_link()); link && link->parent_joint &&
                                                                           link->parent_joint->type == urdf::Joint::FIXED;) {
      base_in_link = UrdfPoseToIsometry(link->parent_joint->parent_to_joint_origin_transform) * base_in_link;
      link = link->getParent();
      if (link && !frames.count(link->name)) frames[link->name] = {-1, -1, base_in_link.inverse(), true};
    }
  }

  for (const auto& [name, link] : urdf.links_) {
    if (link->collision_array.empty()) continue;
    // Climb fixed joints until a link with a known frame.
    Eigen::Isometry3d link_in_ancestor = Eigen::Isometry3d::Identity();
    urdf::LinkConstSharedPtr at = link;
    while (!frames.count(at->name) && at->parent_joint && at->parent_joint->type == urdf::Joint::FIXED) {
      link_in_ancestor = UrdfPoseToIsometry(at->parent_joint->parent_to_joint_origin_transform) * link_in_ancestor;
      at = at->getParent();
    }
    const auto frame = frames.find(at->name);
    if (frame == frames.end()) continue;  // behind a joint no leg chain models: not ours to check
    const Attachment& a = frame->second;
    for (CollisionShape& shape : LinkCollisionShapes(*link, robot)) {
      shape.local = a.link_in_frame * link_in_ancestor * shape.local;
      shape.segment = a.segment;
      if (a.leg < 0) {
        body_.push_back(std::move(shape));
        continue;
      }
      const LegKinematics& leg = kinematics.leg(a.leg);
      shape.foot_contact = name == leg.model().foot_link &&
                           (shape.type == ShapeType::kSphere ||
                            (shape.type == ShapeType::kMesh && leg.model().foot_contact == FootContact::kMeshLowestPoint));
      // The chain's segments after the knee's are the fixed links down to the foot. The knee's own
      // link is left out: its shapes are the shank itself, and robots that model the lower leg as
      // one link (stairbot, Unitree) keep the full margin to the tread under it, as their
      // planners are tuned on.
      shape.foot_part = a.segment > leg.knee_segment();
      if (shape.foot_contact && shape.type == ShapeType::kMesh) {
        shape.contact_point = shape.local.inverse() * (a.link_in_frame * link_in_ancestor * leg.model().foot_sphere_center);
        shape.contact_radius = leg.model().foot_radius;
      }
      auto& shapes = legs_[static_cast<std::size_t>(a.leg)];
      if (shape.foot_contact && foot_shapes_[static_cast<std::size_t>(a.leg)] < 0) {
        foot_shapes_[static_cast<std::size_t>(a.leg)] = static_cast<int>(shapes.size());
      }
      shapes.push_back(std::move(shape));
    }
  }
  for (int l = 0; l < kinematics.leg_count(); ++l) {
    if (legs_[static_cast<std::size_t>(l)].empty()) {
      throw std::invalid_argument(robot.source() + ": leg " + kinematics.leg(l).name() + " (foot <link name=\"" +
                                  kinematics.leg(l).model().foot_link + "\">) has no collision geometry");
    }
  }
}

}  // namespace stairplan
