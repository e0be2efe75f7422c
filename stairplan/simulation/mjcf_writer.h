// Our own writer of MJCF (MuJoCo's model format) from a loaded robot and a staircase: the robot's
// links as bodies with their URDF inertias, revolute joints with limits and damping, collision
// primitives and meshes (their hulls, as inline mesh assets) as geoms, a free-floating base, torque motors bounded by the URDF efforts, and the
// stairs as boxes. MuJoCo is the physics check that nobody on this team wrote.
#pragma once

#include <string>

#include "stairplan/geometry/stair_friction.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"

namespace stairplan {

/// Contact and integration parameters of the simulated world.
struct MjcfSettings {
  double friction = kStairFriction;  ///< sliding friction of every geom (stairplan/geometry/stair_friction.h)
  /// Friction cones: elliptic (true) or MuJoCo's default pyramid. With either, MuJoCo's friction is
  /// a soft constraint that lets a loaded contact creep well below its friction limit unless
  /// `impratio` stiffens it; only the elliptic cone takes impratio in MuJoCo 2.2.
  bool elliptic_cone = true;
  /// Ratio of frictional to normal constraint impedance: 1 (MuJoCo's default) lets a stance foot
  /// creep centimetres under a tangential load of 10 % of its normal force (the stairbot's hind
  /// foot slid off its tread descending); 100, as MuJoCo Menagerie's quadrupeds use, holds it.
  double impratio = 100.0;
  double timestep = 0.001;        ///< simulation step [s] (1 kHz)
  double default_damping = 0.2;   ///< joint damping where the URDF gives none [N m s/rad]
  double armature = 0.01;         ///< rotor inertia added to every joint [kg m^2], for stability
  double min_mass = 1e-3;         ///< MuJoCo needs positive mass on moving bodies [kg]
  double min_inertia = 1e-6;      ///< ... and positive inertia [kg m^2]
  /// Geom pairs closer than this are reported as contacts without any force (MuJoCo's margin with
  /// an equal gap), so that clearances below it can be measured [m]; 0: only real contacts.
  double detect_margin = 0.0;
  double effort_scale = 1.0;      ///< motor torque limits are the URDF efforts times this (what-if studies)

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The MJCF text of `robot` standing in a world that holds `stairs`. Bodies are named after the
/// URDF links, joints after the URDF joints, stair geoms "stair_block_<k>" and "stair_nosing_<k>".
std::string WriteMjcf(const RobotModel& robot, const Staircase& stairs, const MjcfSettings& settings = {});

}  // namespace stairplan
