#include "stairplan/kinematics/robot_model.h"

#include "stairplan/kinematics/urdf_parse.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <urdf_model/model.h>

#include "stairplan/kinematics/leg_kinematics.h"
#include "stairplan/kinematics/urdf_pose.h"
#include "stairplan/kinematics/urdf_to_kdl.h"

namespace stairplan {
namespace {

using LinkPtr = urdf::LinkConstSharedPtr;

bool IsMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
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

const urdf::Collision* SphereCollision(const urdf::Link& link) {
  for (const auto& c : link.collision_array) {
    if (c && c->geometry && c->geometry->type == urdf::Geometry::SPHERE) return c.get();
  }
  return nullptr;
}

double SphereRadius(const urdf::Link& link) {
  const urdf::Collision* sphere = SphereCollision(link);
  return sphere ? static_cast<const urdf::Sphere&>(*sphere->geometry).radius : 0.0;
}

Eigen::Vector3d SphereCenter(const urdf::Link& link) {
  const urdf::Collision* sphere = SphereCollision(link);
  if (!sphere) return Eigen::Vector3d::Zero();
  const urdf::Vector3& p = sphere->origin.position;
  return {p.x, p.y, p.z};
}

// The first movable joint on the way down from the root to `link`, or null: it identifies the leg.
const urdf::Joint* FirstMovableJoint(const LinkPtr& link) {
  const urdf::Joint* first = nullptr;
  for (LinkPtr l = link; l && l->parent_joint; l = l->getParent()) {
    if (IsMovable(*l->parent_joint)) first = l->parent_joint.get();
  }
  return first;
}

// Distance from the leg's first movable joint to `link` at the zero configuration.
double ZeroDistanceFromHip(const LinkPtr& link) {
  Eigen::Isometry3d below_hip = Eigen::Isometry3d::Identity();
  for (LinkPtr l = link; l && l->parent_joint; l = l->getParent()) {
    below_hip = UrdfPoseToIsometry(l->parent_joint->parent_to_joint_origin_transform) * below_hip;
    if (l->parent_joint.get() == FirstMovableJoint(link)) break;
  }
  return below_hip.translation().norm();
}

// True when `a` is a better foot than `b` for the same leg (see LegDetectionSettings).
bool BetterFoot(const LinkPtr& a, const LinkPtr& b) {
  const bool sa = SphereCollision(*a) != nullptr, sb = SphereCollision(*b) != nullptr;
  if (sa != sb) return sa;
  const int ma = MovableJointsAbove(a), mb = MovableJointsAbove(b);
  if (ma != mb) return ma > mb;
  return ZeroDistanceFromHip(a) > ZeroDistanceFromHip(b) + 1e-12;
}

std::vector<LinkPtr> FindFeet(const urdf::ModelInterface& model, const LegDetectionSettings& settings,
                              const std::string& source) {
  std::vector<LinkPtr> feet;
  if (!settings.foot_links.empty()) {
    for (const std::string& name : settings.foot_links) {
      const LinkPtr link = model.getLink(name);
      if (!link) throw std::invalid_argument(source + ": <link name=\"" + name + "\">: no such link (foot_links)");
      if (MovableJointsAbove(link) < 2) {
        throw std::invalid_argument(source + ": <link name=\"" + name + "\">: a foot needs at least two movable joints above it");
      }
      feet.push_back(link);
    }
  } else {
    // One candidate per leg: leaf links grouped by the first movable joint above them.
    std::map<const urdf::Joint*, LinkPtr> best_per_leg;
    for (const auto& [name, link] : model.links_) {
      if (!link->child_links.empty() || MovableJointsAbove(link) < 2) continue;
      if (!settings.foot_name_contains.empty() && name.find(settings.foot_name_contains) == std::string::npos) continue;
      LinkPtr& best = best_per_leg[FirstMovableJoint(link)];
      if (!best || BetterFoot(link, best)) best = link;
    }
    for (const auto& [joint, link] : best_per_leg) feet.push_back(link);
    // Deterministic order regardless of pointer values: by link name.
    std::sort(feet.begin(), feet.end(), [](const LinkPtr& a, const LinkPtr& b) { return a->name < b->name; });
  }
  if (feet.size() != 4) {
    std::ostringstream msg;
    msg << source << ": <link>: expected 4 feet (leaf links below at least two movable joints, one per leg), found "
        << feet.size();
    for (const auto& c : feet) msg << (c == feet.front() ? ": " : ", ") << c->name;
    throw std::invalid_argument(msg.str());
  }
  return feet;
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
  leg.foot_sphere_center = SphereCenter(*foot);
  if (SphereCollision(*foot) != nullptr) leg.foot_contact = FootContact::kSphere;
  std::vector<LinkPtr> path = PathFromRoot(foot);
  path.erase(path.begin(), std::find(path.begin(), path.end(), base) + 1);
  Eigen::Isometry3d base_T = Eigen::Isometry3d::Identity();
  bool seen_movable = false;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (const auto& link : path) {
    const urdf::Joint& joint = *link->parent_joint;
    base_T = base_T * UrdfPoseToIsometry(joint.parent_to_joint_origin_transform);
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

// The vertices of `link`'s collision meshes in the link frame.
std::vector<Eigen::Vector3d> MeshVertices(const urdf::Link& link, const RobotMeshes& meshes) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < link.collision_array.size(); ++i) {
    const auto mesh = meshes.Find(link.name, static_cast<int>(i));
    if (!mesh) continue;
    const Eigen::Isometry3d origin = UrdfPoseToIsometry(link.collision_array[i]->origin);
    for (const Eigen::Vector3d& v : mesh->vertices) points.push_back(origin * v);
  }
  return points;
}

// The mesh's extent along unit direction d: its support h(d) = max p.d.
double Support(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& d) {
  double h = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) h = std::max(h, p.dot(d));
  return h;
}

// A foot rolls about the knee axis as the leg swings, so its contact wanders over its rim. Where
// the rim is a circle (Solo's wheel-shaped foot), the support along directions turned about that
// axis from `down` is h = c.d + r for a fixed centre c and radius r: fitted by least squares over
// +-40 degrees (about the link origin if that fits), the foot is that sphere when no direction
// misses by more than 0.3 mm. Along the axis the centre lies midway across the foot. Returns
// false (the foot is not round) otherwise.
bool FitRollingSphere(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& down,
                      const Eigen::Vector3d& axis_in, Eigen::Vector3d* centre, double* radius) {
  constexpr int kSamples = 17;
  constexpr double kRange = 40.0 * M_PI / 180.0, kTolerance = 3e-4;  // [rad], [m]
  const Eigen::Vector3d axis = (axis_in - axis_in.dot(down) * down).normalized();
  const Eigen::Vector3d side = axis.cross(down);
  Eigen::Matrix<double, kSamples, 3> a;
  Eigen::Matrix<double, kSamples, 1> h;
  for (int k = 0; k < kSamples; ++k) {
    const double theta = kRange * (2.0 * k / (kSamples - 1) - 1.0);
    a.row(k) << std::cos(theta), std::sin(theta), 1.0;
    h(k) = Support(points, std::cos(theta) * down + std::sin(theta) * side);
  }
  const double across = 0.5 * (Support(points, axis) - Support(points, -axis));
  // Feet are drawn about their link origin: a sphere there is tried first, as the planners need
  // not re-aim a foot whose contact sphere is centred on its origin.
  const double about_origin = h.mean();
  if ((h.array() - about_origin).abs().maxCoeff() <= kTolerance && about_origin > kTolerance) {
    *centre = across * axis;
    *radius = about_origin;
    return true;
  }
  const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(h);
  if (!((a * fit - h).cwiseAbs().maxCoeff() <= kTolerance) || !(fit.z() > kTolerance)) return false;
  *centre = fit.x() * down + fit.y() * side + across * axis;
  *radius = fit.z();
  return true;
}

// A foot whose only collision is a mesh touches the ground with the mesh's lowest point along
// the leg (from the hip through the foot) in the nominal stance. Vertices within a tenth of a
// millimetre of the lowest are averaged: a rounded foot's rim has many, and their mean lies in the
// foot's middle plane rather than on one side of it. A foot round about the knee axis is the
// sphere fitted to its rim, whose bottom that point is: its contact then rolls with the foot
// instead of staying on one rim point that dips below the ground as the shank turns.
void SetMeshFootContacts(const urdf::ModelInterface& urdf, const std::string& base_link, const RobotMeshes& meshes,
                         std::vector<LegModel>& legs) {
  std::shared_ptr<const KDL::Tree> tree;
  for (LegModel& leg : legs) {
    if (leg.foot_contact == FootContact::kSphere || leg.joint_names.size() != 3) continue;  // RobotKinematics names the latter
    const std::vector<Eigen::Vector3d> points = MeshVertices(*urdf.getLink(leg.foot_link), meshes);
    if (points.empty()) continue;
    if (!tree) tree = std::make_shared<const KDL::Tree>(UrdfToKdlTree(urdf));
    const LegKinematics kinematics(leg, *tree, base_link);
    LegWorkspace ws(kinematics);
    const Eigen::Isometry3d foot_B = kinematics.FootPose(kinematics.nominal(), ws);
    const Eigen::Vector3d down_F = foot_B.linear().transpose() * (foot_B.translation() - leg.hip_B).normalized();
    const double lowest = Support(points, down_F);
    constexpr double kTie = 1e-4;  // [m]
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (const Eigen::Vector3d& p : points) {
      if (p.dot(down_F) < lowest - kTie) continue;
      sum += p;
      ++count;
    }
    // On the support plane itself: the averaged point is pushed back out to the lowest depth.
    const Eigen::Vector3d mean = sum / count;
    leg.foot_contact_point = mean + (lowest - mean.dot(down_F)) * down_F;
    leg.foot_sphere_center = leg.foot_contact_point;
    leg.foot_radius = 0.0;
    leg.foot_contact = FootContact::kMeshLowestPoint;
    // The knee axis in the foot frame, from how the foot turns with the last joint.
    Eigen::Vector3d q = kinematics.nominal();
    q.z() += 1e-3;
    const Eigen::AngleAxisd turn(foot_B.linear().transpose() * kinematics.FootPose(q, ws).linear());
    Eigen::Vector3d centre;
    double radius = 0.0;
    if (turn.angle() > 0.0 && FitRollingSphere(points, down_F, turn.axis(), &centre, &radius)) {
      leg.foot_sphere_center = centre.norm() < kTie ? Eigen::Vector3d::Zero() : centre;
      leg.foot_radius = radius;
    }
  }
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open the URDF file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

const char* ToString(FootContact contact) {
  switch (contact) {
    case FootContact::kLinkOrigin: return "link_origin";
    case FootContact::kSphere: return "sphere";
    case FootContact::kMeshLowestPoint: return "mesh_lowest_point";
  }
  return "unknown";
}

RobotModel RobotModel::FromUrdfFile(const std::string& path, const LegDetectionSettings& settings,
                                    const MeshSettings& meshes) {
  return FromUrdfString(ReadText(path), path, settings, meshes);
}

RobotModel RobotModel::FromUrdfString(const std::string& xml, const std::string& source_name,
                                      const LegDetectionSettings& settings, const MeshSettings& meshes) {
  const std::shared_ptr<const urdf::ModelInterface> parsed = ParseUrdf(xml, source_name);
  RobotModel model;
  model.urdf_ = parsed;
  model.meshes_ = RobotMeshes::Load(*parsed, std::filesystem::path(source_name).parent_path().string(), meshes, source_name);
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
  SetMeshFootContacts(*parsed, model.base_link_, *model.meshes_, model.legs_);
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
