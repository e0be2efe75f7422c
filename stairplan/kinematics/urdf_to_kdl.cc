#include "stairplan/kinematics/urdf_to_kdl.h"

#include <stdexcept>

#include <kdl/frames.hpp>
#include <kdl/joint.hpp>
#include <kdl/rigidbodyinertia.hpp>
#include <kdl/segment.hpp>
#include <urdf_model/model.h>

namespace stairplan {
namespace {

KDL::Vector ToKdl(const urdf::Vector3& v) { return KDL::Vector(v.x, v.y, v.z); }

KDL::Frame ToKdl(const urdf::Pose& pose) {
  return KDL::Frame(KDL::Rotation::Quaternion(pose.rotation.x, pose.rotation.y, pose.rotation.z, pose.rotation.w),
                    ToKdl(pose.position));
}

// KDL joints carry their axis and origin in the parent link's frame; the segment's tip frame is the
// joint origin, so the child frame ends up at origin * motion(q), as URDF defines it.
KDL::Joint ToKdl(const urdf::Joint& joint) {
  const KDL::Frame origin = ToKdl(joint.parent_to_joint_origin_transform);
  switch (joint.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
      return KDL::Joint(joint.name, origin.p, origin.M * ToKdl(joint.axis), KDL::Joint::RotAxis);
    case urdf::Joint::PRISMATIC:
      return KDL::Joint(joint.name, origin.p, origin.M * ToKdl(joint.axis), KDL::Joint::TransAxis);
    default:
      return KDL::Joint(joint.name, KDL::Joint::None);
  }
}

KDL::RigidBodyInertia ToKdl(const urdf::Inertial* inertial) {
  if (!inertial) return KDL::RigidBodyInertia::Zero();
  const KDL::Frame origin = ToKdl(inertial->origin);
  // URDF gives the inertia about the centre of mass in the inertial frame; KDL wants it about the
  // centre of mass in the link frame, which the rotation takes care of.
  const KDL::RigidBodyInertia in_inertial_frame(
      inertial->mass, origin.p,
      KDL::RotationalInertia(inertial->ixx, inertial->iyy, inertial->izz, inertial->ixy, inertial->ixz, inertial->iyz));
  return origin.M * in_inertial_frame;
}

void AddChildren(const urdf::Link& link, KDL::Tree& tree) {
  for (const urdf::LinkSharedPtr& child : link.child_links) {
    const urdf::Joint& joint = *child->parent_joint;
    const KDL::Segment segment(child->name, ToKdl(joint), ToKdl(joint.parent_to_joint_origin_transform),
                               ToKdl(child->inertial.get()));
    if (!tree.addSegment(segment, link.name)) {
      throw std::invalid_argument("UrdfToKdlTree: <joint name=\"" + joint.name + "\">: KDL refused the segment '" +
                                  child->name + "' (duplicate link name?)");
    }
    AddChildren(*child, tree);
  }
}

}  // namespace

KDL::Tree UrdfToKdlTree(const urdf::ModelInterface& model) {
  const urdf::LinkConstSharedPtr root = model.getRoot();
  if (!root) throw std::invalid_argument("UrdfToKdlTree: the URDF model has no root link");
  KDL::Tree tree(root->name);
  AddChildren(*root, tree);
  return tree;
}

}  // namespace stairplan
