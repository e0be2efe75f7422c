// A legged robot read from URDF (urdfdom): its base, its legs found automatically and named
// LF, RF, LH, RH by where their hips sit in the base frame, joint limits and foot geometry.
// This is the const model; kinematics solvers keep their own workspaces.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stairplan/kinematics/robot_meshes.h"

namespace urdf {
class ModelInterface;
}

namespace stairplan {

/// Limits of one movable joint, from the URDF's `<limit>` element.
struct JointLimits {
  double lower = 0.0;     ///< [rad]
  double upper = 0.0;     ///< [rad]
  double effort = 0.0;    ///< [N m]
  double velocity = 0.0;  ///< [rad/s]
};

/// What a foot touches the ground with.
enum class FootContact {
  kLinkOrigin,        ///< no collision geometry to go by: the foot link's origin
  kSphere,            ///< the lowest point of the foot's sphere collision
  /// the foot mesh's lowest point along the leg in the nominal stance; where the mesh is round
  /// about the knee axis, the bottom of the sphere fitted to it, which that point lies on
  kMeshLowestPoint,
};
/// "link_origin", "sphere" or "mesh_lowest_point".
const char* ToString(FootContact contact);

/// One leg: the chain of links and movable joints from the base to the foot.
struct LegModel {
  std::string name;                      ///< "LF", "RF", "LH" or "RH"
  std::string foot_link;                 ///< the leaf link at the end of the chain
  std::vector<std::string> link_names;   ///< links from the base's child to the foot, in order
  std::vector<std::string> joint_names;  ///< movable joints from base to foot, in order
  std::vector<JointLimits> limits;       ///< one per movable joint
  Eigen::Vector3d hip_B = Eigen::Vector3d::Zero();       ///< first movable joint's origin in the base frame [m]
  Eigen::Vector3d foot_zero_B = Eigen::Vector3d::Zero(); ///< foot origin at zero joint angles, base frame [m]
  double foot_radius = 0.0;  ///< radius of the foot's sphere collision, 0 when it has none [m]
  /// Centre of the foot's sphere collision in the foot link frame (ANYmal's sits above the link
  /// origin, Go2's slightly behind it). A mesh foot that is round where it rolls (about the knee
  /// axis) is the sphere fitted to that rim; any other mesh foot is a sphere of radius 0 at its
  /// contact point (FootContact::kMeshLowestPoint), so every planner places it as it places a
  /// sphere. Zero when the foot has neither [m].
  Eigen::Vector3d foot_sphere_center = Eigen::Vector3d::Zero();
  /// Where a mesh foot touches the ground in the nominal stance, in the foot link frame: its
  /// lowest point along the leg (on the fitted sphere of a round foot). Zero for other feet [m].
  Eigen::Vector3d foot_contact_point = Eigen::Vector3d::Zero();
  FootContact foot_contact = FootContact::kLinkOrigin;  ///< where foot_sphere_center comes from
  double max_reach = 0.0;    ///< upper bound on the hip-to-foot distance: sum of the chain's offsets [m]
  double mass = 0.0;         ///< mass of the leg's links [kg]
};

/// How feet are recognised when the automatic rule is not what a robot needs. The automatic rule:
/// a foot is a leaf link below at least two movable joints; leaf links are grouped by the first
/// movable joint above them (one group per leg) and each group's foot is the link with a sphere
/// collision, then the one below the most movable joints, then the one farthest from the hip at the
/// zero configuration. Sensor boxes, rotors and covers hanging off a leg are thereby passed over.
struct LegDetectionSettings {
  /// When non-empty, a foot is a link whose name contains this substring (case-sensitive).
  std::string foot_name_contains;
  /// When non-empty, exactly these links are the feet (any order); overrides foot_name_contains.
  std::vector<std::string> foot_links;
};

/// A robot model loaded from URDF. Immutable after loading; cheap to copy (shared URDF and meshes).
class RobotModel {
 public:
  /// Loads and checks a URDF file and reads its collision meshes (see RobotMeshes). Throws
  /// std::invalid_argument naming the file and the element (missing file, malformed XML, a joint
  /// naming a missing link, no four feet, an unresolved mesh URI, a bad mesh file, ...).
  static RobotModel FromUrdfFile(const std::string& path, const LegDetectionSettings& settings = {},
                                 const MeshSettings& meshes = {});
  /// The same from URDF text; `source_name` is used in error messages, and its folder (when it is
  /// a path) is where relative mesh paths start.
  static RobotModel FromUrdfString(const std::string& xml, const std::string& source_name,
                                   const LegDetectionSettings& settings = {}, const MeshSettings& meshes = {});

  /// The robot's name, from the URDF.
  const std::string& name() const { return name_; }
  /// Where the robot came from (the file, or the name given for URDF text), for messages.
  const std::string& source() const { return source_; }
  /// The URDF link the legs hang from.
  const std::string& base_link() const { return base_link_; }
  /// The four legs in the order LF, RF, LH, RH.
  const std::vector<LegModel>& legs() const { return legs_; }
  /// The leg with that name; throws std::invalid_argument when there is none.
  const LegModel& leg(const std::string& name) const;
  /// Sum of every link's mass [kg].
  double total_mass() const { return total_mass_; }
  /// Distance along x between the mean front and mean hind hip [m].
  double hip_length() const;
  /// Distance along y between the mean left and mean right hip [m].
  double hip_width() const;
  /// The parsed URDF, for the kinematics and collision builders.
  const urdf::ModelInterface& urdf() const { return *urdf_; }
  /// The parsed URDF, shared.
  std::shared_ptr<const urdf::ModelInterface> urdf_ptr() const { return urdf_; }
  /// The collision meshes, read once when the model was loaded (empty for a robot of primitives).
  const RobotMeshes& meshes() const { return *meshes_; }

 private:
  std::shared_ptr<const urdf::ModelInterface> urdf_;
  std::shared_ptr<const RobotMeshes> meshes_ = std::make_shared<const RobotMeshes>();
  std::string name_;
  std::string source_;
  std::string base_link_;
  std::vector<LegModel> legs_;
  double total_mass_ = 0.0;
};

}  // namespace stairplan
