#include "stairplan/simulation/mjcf_writer.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <urdf_model/model.h>

#include "stairplan/collision/mesh_shape.h"
#include "stairplan/geometry/field_error.h"
#include "stairplan/kinematics/checked_xml.h"

namespace stairplan {
namespace {

std::string Vec(double x, double y, double z) {
  std::ostringstream out;
  out << std::setprecision(10) << x << " " << y << " " << z;
  return out.str();
}

std::string Pos(const urdf::Pose& p) { return Vec(p.position.x, p.position.y, p.position.z); }

std::string Quat(const urdf::Pose& p) {
  double x = 0, y = 0, z = 0, w = 1;
  p.rotation.getQuaternion(x, y, z, w);
  std::ostringstream out;
  out << std::setprecision(10) << w << " " << x << " " << y << " " << z;
  return out.str();
}

bool IsMovable(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS || j.type == urdf::Joint::PRISMATIC;
}

// Some published URDFs carry inertias that no rigid body has (ANYmal B's edited base): MuJoCo
// rejects them, so the principal moments are raised until positive and triangle-consistent.
Eigen::Matrix3d PhysicalInertia(const Eigen::Matrix3d& inertia, double min_inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia);
  Eigen::Vector3d moments = eig.eigenvalues().cwiseMax(min_inertia);
  for (int i = 0; i < 3; ++i) {
    const double others = moments.sum() - moments(i);
    moments(i) = std::min(moments(i), others);  // A <= B + C for every principal moment
  }
  return eig.eigenvectors() * moments.asDiagonal() * eig.eigenvectors().transpose();
}

// MJCF takes a full inertia only in the body frame, so the URDF's inertial rotation is applied here.
void WriteInertial(std::ostringstream& out, const urdf::Link& link, const MjcfSettings& s, const std::string& indent) {
  if (!link.inertial) return;
  const urdf::Inertial& i = *link.inertial;
  double x = 0, y = 0, z = 0, w = 1;
  i.origin.rotation.getQuaternion(x, y, z, w);
  const Eigen::Matrix3d r = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  Eigen::Matrix3d inertia;
  inertia << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
  const Eigen::Matrix3d body = PhysicalInertia(r * inertia * r.transpose(), s.min_inertia);
  out << indent << "<inertial pos='" << Pos(i.origin) << "' mass='" << std::max(i.mass, s.min_mass)
      << "' fullinertia='" << body(0, 0) << " " << body(1, 1) << " " << body(2, 2) << " " << body(0, 1) << " "
      << body(0, 2) << " " << body(1, 2) << "'/>\n";
}

std::string MeshAssetName(const std::string& link, std::size_t index) {
  return link + "_mesh_" + std::to_string(index);
}

// Every collision mesh as an asset given by its hull's vertices: MuJoCo collides with a mesh's
// convex hull whatever it is given, so the hull is all it needs, and the file's format does not
// matter (MuJoCo 2.2 reads no COLLADA).
void WriteMeshAssets(std::ostringstream& out, const RobotModel& robot) {
  if (robot.meshes().size() == 0) return;
  out << "  <asset>\n";
  for (const auto& [name, link] : robot.urdf().links_) {
    for (std::size_t i = 0; i < link->collision_array.size(); ++i) {
      const std::shared_ptr<const TriangleMesh> mesh = robot.meshes().Find(name, static_cast<int>(i));
      if (!mesh) continue;
      const std::shared_ptr<const MeshShape> hull = GetMeshShape(mesh, MeshCollision::kConvexHull);
      out << "    <mesh name='" << MeshAssetName(name, i) << "' vertex='";
      for (const Eigen::Vector3d& v : hull->hull_vertices) {
        const Eigen::Vector3d p = v + hull->centre;
        out << p.x() << " " << p.y() << " " << p.z() << " ";
      }
      out << "'/>\n";
    }
  }
  out << "  </asset>\n";
}

void WriteGeoms(std::ostringstream& out, const urdf::Link& link, const std::string& indent) {
  int n = 0;
  for (std::size_t index = 0; index < link.collision_array.size(); ++index) {
    const auto& c = link.collision_array[index];
    if (!c || !c->geometry) continue;
    std::string type, size;
    // Meshes collide with the stairs and primitives but not with each other: hulls of adjacent
    // links overlap where the real parts interleave (Solo 12's thigh hull reaches 9 mm into its
    // base's), which MuJoCo would push apart. The validator checks leg against leg.
    std::string filter;
    if (c->geometry->type == urdf::Geometry::BOX) {
      const auto& b = static_cast<const urdf::Box&>(*c->geometry);
      type = "box";
      size = Vec(b.dim.x / 2, b.dim.y / 2, b.dim.z / 2);
    } else if (c->geometry->type == urdf::Geometry::CYLINDER) {
      const auto& cyl = static_cast<const urdf::Cylinder&>(*c->geometry);
      type = "cylinder";
      std::ostringstream sz;
      sz << std::setprecision(10) << cyl.radius << " " << cyl.length / 2;
      size = sz.str();
    } else if (c->geometry->type == urdf::Geometry::SPHERE) {
      type = "sphere";
      std::ostringstream sz;
      sz << std::setprecision(10) << static_cast<const urdf::Sphere&>(*c->geometry).radius;
      size = sz.str();
    } else {
      type = "mesh";
      size = "0 0 0";
      filter = "' mesh='" + XmlEscaped(MeshAssetName(link.name, index)) + "' contype='2' conaffinity='1";
    }
    out << indent << "<geom name='" << XmlEscaped(link.name) << "_collision_" << n++ << "' type='" << type << "' size='" << size
        << "' pos='" << Pos(c->origin) << "' quat='" << Quat(c->origin) << filter << "'/>\n";
  }
}

void WriteJoint(std::ostringstream& out, const urdf::Joint& j, const MjcfSettings& s, const std::string& indent) {
  const bool hinge = j.type != urdf::Joint::PRISMATIC;
  out << indent << "<joint name='" << XmlEscaped(j.name) << "' type='" << (hinge ? "hinge" : "slide") << "' axis='"
      << Vec(j.axis.x, j.axis.y, j.axis.z) << "'";
  if (j.type != urdf::Joint::CONTINUOUS && j.limits && j.limits->upper > j.limits->lower) {
    out << " limited='true' range='" << j.limits->lower << " " << j.limits->upper << "'";
  }
  const double damping = (j.dynamics && j.dynamics->damping > 0.0) ? j.dynamics->damping : s.default_damping;
  out << " damping='" << damping << "' armature='" << s.armature << "'/>\n";
}

// One URDF link and its subtree as nested bodies. Fixed joints become bodies without joints.
void WriteBody(std::ostringstream& out, const urdf::Link& link, const MjcfSettings& s, int depth) {
  const std::string indent(2 * static_cast<std::size_t>(depth), ' ');
  const urdf::Joint& j = *link.parent_joint;
  const urdf::Pose& origin = j.parent_to_joint_origin_transform;
  out << indent << "<body name='" << XmlEscaped(link.name) << "' pos='" << Pos(origin) << "' quat='" << Quat(origin) << "'>\n";
  if (IsMovable(j)) WriteJoint(out, j, s, indent + "  ");
  WriteInertial(out, link, s, indent + "  ");
  WriteGeoms(out, link, indent + "  ");
  for (const auto& child : link.child_links) WriteBody(out, *child, s, depth + 1);
  out << indent << "</body>\n";
}

// MuJoCo never lets a body touch its parent; a link and its grandparent are left apart too: their
// collision shapes may overlap by design (ANYmal B's base boxes reach 2.5 mm into its thighs at
// every pose), and MuJoCo would push them apart with contact forces the real robot never feels.
// `parent`: link's parent body in the MJCF (null for the base, whose URDF parent is not written).
void WriteExcludes(std::ostringstream& out, const urdf::Link& link, const urdf::Link* parent) {
  for (const auto& child : link.child_links) {
    if (parent != nullptr) {
      out << "    <exclude body1='" << XmlEscaped(parent->name) << "' body2='" << XmlEscaped(child->name) << "'/>\n";
    }
    WriteExcludes(out, *child, &link);
  }
}

void WriteStairs(std::ostringstream& out, const Staircase& stairs) {
  for (const Box3& box : stairs.Solids()) {
    const Eigen::Vector3d c = box.Center(), h = 0.5 * box.Size();
    out << "    <geom name='stair_" << (box.kind == SolidKind::kBlock ? "block_" : "nosing_") << box.surface_index
        << "' type='box' pos='" << Vec(c.x(), c.y(), c.z()) << "' size='" << Vec(h.x(), h.y(), h.z())
        << "' rgba='0.7 0.7 0.7 1'/>\n";
  }
}

void WriteMotors(std::ostringstream& out, const RobotModel& robot, double effort_scale) {
  out << "  <actuator>\n";
  for (const LegModel& leg : robot.legs()) {
    for (std::size_t i = 0; i < leg.joint_names.size(); ++i) {
      const double effort = effort_scale * (leg.limits[i].effort > 0.0 ? leg.limits[i].effort : 1e3);
      out << "    <motor name='" << XmlEscaped(leg.joint_names[i]) << "_motor' joint='" << XmlEscaped(leg.joint_names[i])
          << "' ctrllimited='true' ctrlrange='" << -effort << " " << effort << "'/>\n";
    }
  }
  out << "  </actuator>\n";
}

}  // namespace

void MjcfSettings::Validate() const {
  const auto check = [](const char* name, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi) throw FieldError(name, "out of range (got " + std::to_string(v) + ")");
  };
  check("friction", friction, 0.0, 10.0);
  check("timestep", timestep, 1e-5, 0.05);
  check("default_damping", default_damping, 0.0, 100.0);
  check("armature", armature, 0.0, 10.0);
  check("min_mass", min_mass, 1e-9, 1.0);
  check("min_inertia", min_inertia, 1e-12, 1.0);
  check("effort_scale", effort_scale, 1e-3, 1e3);
  check("detect_margin", detect_margin, 0.0, 0.1);
  check("impratio", impratio, 1.0, 1e4);
}

std::string WriteMjcf(const RobotModel& robot, const Staircase& stairs, const MjcfSettings& settings) {
  settings.Validate();
  const urdf::ModelInterface& model = robot.urdf();
  const urdf::LinkConstSharedPtr base = model.getLink(robot.base_link());
  std::ostringstream out;
  out << std::setprecision(10);
  out << "<mujoco model='" << XmlEscaped(robot.name()) << "'>\n"
      << "  <compiler angle='radian' inertiafromgeom='false' boundmass='" << settings.min_mass
      << "' boundinertia='" << settings.min_inertia << "'/>\n"
      << "  <option timestep='" << settings.timestep << "' gravity='0 0 -9.81' cone='"
      << (settings.elliptic_cone ? "elliptic" : "pyramidal") << "' impratio='" << settings.impratio << "'/>\n"
      << "  <default><geom friction='" << settings.friction << " 0.005 0.0001' condim='3' margin='"
      << settings.detect_margin << "' gap='" << settings.detect_margin << "'/></default>\n";
  WriteMeshAssets(out, robot);
  out << "  <worldbody>\n"
      << "    <light pos='0 -3 4' dir='0 0.6 -0.8' directional='true'/>\n";
  WriteStairs(out, stairs);
  out << "    <body name='" << XmlEscaped(base->name) << "' pos='0 0 1'>\n      <freejoint name='floating_base'/>\n";
  WriteInertial(out, *base, settings, "      ");
  WriteGeoms(out, *base, "      ");
  for (const auto& child : base->child_links) WriteBody(out, *child, settings, 3);
  out << "    </body>\n  </worldbody>\n  <contact>\n";
  WriteExcludes(out, *base, nullptr);
  out << "  </contact>\n";
  WriteMotors(out, robot, settings.effort_scale);
  out << "</mujoco>\n";
  return out.str();
}

}  // namespace stairplan
