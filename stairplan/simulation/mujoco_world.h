// A MuJoCo world holding one robot and one staircase, built from our MJCF writer. Owns the
// mjModel and mjData; gives name-based access to joints, motors and contacts.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/simulation/mjcf_writer.h"

struct mjModel_;
struct mjData_;

namespace stairplan {

/// One contact between a robot body and a stair geom.
struct StairContact {
  std::string body;   ///< the robot body (URDF link) touching the stairs
  std::string geom;   ///< the stair geom ("stair_block_3", "stair_nosing_2")
  double depth = 0.0; ///< penetration depth [m], positive
};

/// A MuJoCo world holding one robot and one staircase, with name-based access to joints, motors and contacts.
class MujocoWorld {
 public:
  /// Builds the world; throws std::runtime_error with MuJoCo's message if it rejects the model.
  MujocoWorld(const RobotModel& robot, const Staircase& stairs, const MjcfSettings& settings = {});
  ~MujocoWorld();
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  /// MuJoCo's model.
  const mjModel_* model() const { return model_; }
  /// MuJoCo's state, advanced by Step().
  mjData_* data() { return data_; }
  /// The MJCF the world was built from.
  const std::string& mjcf() const { return mjcf_; }

  ///@{
  /// Index of a joint's angle in qpos and of its velocity in qvel; throws when unknown.
  int QposIndex(const std::string& joint) const;
  int QvelIndex(const std::string& joint) const;
  ///@}
  /// Index of the motor driving `joint` in ctrl; throws when unknown.
  int MotorIndex(const std::string& joint) const;

  /// Places the floating base (position, yaw, pitch; pitch nose-up negative) at rest.
  void SetBasePose(const Eigen::Vector3d& position_W, double yaw, double pitch);
  /// The floating base's position in the world [m].
  Eigen::Vector3d BasePosition() const;
  /// Roll, pitch, yaw of the base [rad].
  Eigen::Vector3d BaseRollPitchYaw() const;
  /// Recomputes positions and contacts without advancing time.
  void Forward();
  /// Advances the simulation by one time step.
  void Step();
  /// Simulated time [s].
  double time() const;
  /// Current contacts between robot bodies and stair geoms.
  std::vector<StairContact> StairContacts() const;
  /// Total mass of the robot's bodies [kg].
  double RobotMass() const;

 private:
  mjModel_* model_ = nullptr;
  mjData_* data_ = nullptr;
  std::string mjcf_;
  int base_body_ = -1;
};

}  // namespace stairplan
