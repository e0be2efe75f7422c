#include "kinematics/robot_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

namespace stairplan {
namespace {

using LinkPtr = urdf::LinkConstSharedPtr;

bool IsMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  t.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  return t;
}

// Links from the root down to `link`, root first.
std::vector<LinkPtr> PathFromRoot(LinkPtr link) {
  std::vector<LinkPtr> path;
  for (; link; link = link->getParent()) path.push_back(link);
  std::reverse(path.begin(), path.end());
  return path;
}

int MovableJointsAbove(const LinkPtr& link) {
  int count = 0;
  for (LinkPtr l = link; l && l->parent_joint; l = l->getParent()) count += IsMovable(*l->parent_joint) ? 1 : 0;
  return count;
}

bool HasSphereCollision(const urdf::Link& link) {
  for (const auto& c : link.collision_array) {
    if (c && c->geometry && c->geometry->type == urdf::Geometry::SPHERE) return true;
  }
  return false;
}

double SphereRadius(const urdf::Link& link) {
  for (const auto& c : link.collision_array) {
    if (c && c->geometry && c->geometry->type == urdf::Geometry::SPHERE) {
      return static_cast<const urdf::Sphere&>(*c->geometry).radius;
    }
  }
  return 0.0;
}

std::vector<LinkPtr> FindFeet(const urdf::ModelInterface& model, const LegDetectionSettings& settings,
                              const std::string& source) {
  std::vector<LinkPtr> candidates;
  for (const auto& [name, link] : model.links_) {
    if (!link->child_links.empty() || MovableJointsAbove(link) < 2) continue;
    if (!settings.foot_name_contains.empty() && name.find(settings.foot_name_contains) == std::string::npos) continue;
    candidates.push_back(link);
  }
  if (candidates.size() > 4) {
    std::vector<LinkPtr> spheres;
    for (const auto& c : candidates) {
      if (HasSphereCollision(*c)) spheres.push_back(c);
    }
    if (spheres.size() == 4) candidates = spheres;
  }
  if (candidates.size() != 4) {
    std::ostringstream msg;
    msg << source << ": <link>: expected 4 feet (leaf links below at least two movable joints), found "
        << candidates.size();
    for (const auto& c : candidates) msg << (c == candidates.front() ? ": " : ", ") << c->name;
    throw std::invalid_argument(msg.str());
  }
  return candidates;
}

// The deepest link that every foot hangs from.
LinkPtr CommonBase(const std::vector<LinkPtr>& feet) {
  std::vector<LinkPtr> common = PathFromRoot(feet.front());
  for (const auto& foot : feet) {
    const std::vector<LinkPtr> path = PathFromRoot(foot);
    std::size_t n = 0;
    while (n < common.size() && n < path.size() && common[n] == path[n]) ++n;
    common.resize(n);
  }
  return common.back();
}

LegModel BuildLeg(const LinkPtr& base, const LinkPtr& foot) {
  LegModel leg;
  leg.foot_link = foot->name;
  leg.foot_radius = SphereRadius(*foot);
  std::vector<LinkPtr> path = PathFromRoot(foot);
  path.erase(path.begin(), std::find(path.begin(), path.end(), base) + 1);
  Eigen::Isometry3d base_T = Eigen::Isometry3d::Identity();
  bool seen_movable = false;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (const auto& link : path) {
    const urdf::Joint& joint = *link->parent_joint;
    base_T = base_T * ToIsometry(joint.parent_to_joint_origin_transform);
    leg.link_names.push_back(link->name);
    if (link->inertial) leg.mass += link->inertial->mass;
    if (seen_movable) leg.max_reach += (base_T.translation() - previous).norm();
    previous = base_T.translation();
    if (!IsMovable(joint)) continue;
    if (!seen_movable) leg.hip_B = base_T.translation();
    seen_movable = true;
    leg.joint_names.push_back(joint.name);
    JointLimits limits;
    if (joint.type == urdf::Joint::CONTINUOUS || !joint.limits) {
      limits.lower = -M_PI;
      limits.upper = M_PI;
    } else {
      limits.lower = joint.limits->lower;
      limits.upper = joint.limits->upper;
    }
    if (joint.limits) {
      limits.effort = joint.limits->effort;
      limits.velocity = joint.limits->velocity;
    }
    leg.limits.push_back(limits);
  }
  leg.foot_zero_B = base_T.translation();
  return leg;
}

void NameLegs(std::vector<LegModel>& legs, const std::string& source) {
  for (LegModel& leg : legs) {
    leg.name = std::string(leg.hip_B.y() >= 0.0 ? "L" : "R") + (leg.hip_B.x() >= 0.0 ? "F" : "H");
  }
  const std::vector<std::string> order = {"LF", "RF", "LH", "RH"};
  std::vector<LegModel> sorted;
  for (const std::string& name : order) {
    const auto it = std::find_if(legs.begin(), legs.end(), [&](const LegModel& l) { return l.name == name; });
    if (it == legs.end()) {
      throw std::invalid_argument(source + ": <joint>: no leg whose hip lies at the " + name +
                                  " corner of the base frame (hips must be front/hind and left/right)");
    }
    sorted.push_back(*it);
  }
  legs = sorted;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open the URDF file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

RobotModel RobotModel::FromUrdfFile(const std::string& path, const LegDetectionSettings& settings) {
  return FromUrdfString(ReadText(path), path, settings);
}

RobotModel RobotModel::FromUrdfString(const std::string& xml, const std::string& source_name,
                                      const LegDetectionSettings& settings) {
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw std::invalid_argument(source_name + ": <robot>: the URDF is empty");
  }
  urdf::ModelInterfaceSharedPtr parsed = urdf::parseURDF(xml);
  if (!parsed || !parsed->getRoot()) {
    throw std::invalid_argument(source_name + ": <robot>: not a valid URDF (malformed XML, or a joint or link that does not resolve)");
  }
  RobotModel model;
  model.urdf_ = parsed;
  model.name_ = parsed->getName();
  model.source_ = source_name;
  for (const auto& [name, link] : parsed->links_) {
    if (link->inertial) model.total_mass_ += link->inertial->mass;
  }
  const std::vector<LinkPtr> feet = FindFeet(*parsed, settings, source_name);
  const LinkPtr base = CommonBase(feet);
  model.base_link_ = base->name;
  for (const auto& foot : feet) model.legs_.push_back(BuildLeg(base, foot));
  NameLegs(model.legs_, source_name);
  return model;
}

const LegModel& RobotModel::leg(const std::string& name) const {
  for (const LegModel& l : legs_) {
    if (l.name == name) return l;
  }
  throw std::invalid_argument("RobotModel::leg: no leg named '" + name + "'");
}

double RobotModel::hip_length() const {
  return 0.5 * (leg("LF").hip_B.x() + leg("RF").hip_B.x()) - 0.5 * (leg("LH").hip_B.x() + leg("RH").hip_B.x());
}

double RobotModel::hip_width() const {
  return 0.5 * (leg("LF").hip_B.y() + leg("LH").hip_B.y()) - 0.5 * (leg("RF").hip_B.y() + leg("RH").hip_B.y());
}

}  // namespace stairplan
