// What happened when MuJoCo executed a plan: the overall status with its first cause, every
// footstep's landing against its target, leg-stair contacts other than feet by link, peak joint
// torques against the URDF's effort limits, the simulation speed, and optional recorded states.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/simulation/impact_record.h"
#include "stairplan/simulation/stance_force_source.h"

namespace stairplan {

/// How a run ended.
enum class SimStatus {
  kSuccess,  ///< reached the plan's final pose on the landing with the body upright
  kFall,     ///< body roll or pitch beyond the limit, or the body touched the stairs
  kStalled,  ///< upright at the end but not where the plan ends
};
/// Returns "success", "fall" or "stalled".
const char* ToString(SimStatus status);

/// One footstep as executed.
struct FootLanding {
  std::string leg;  ///< "LF", "RF", "LH" or "RH"
  double t_planned = 0.0;        ///< the plan's touchdown time [s, plan time]
  double t_contact = -1.0;       ///< when contact made it a stance leg; -1 when it never touched [s, plan time]
  bool touched = false;          ///< contact happened (false: forced to stance after the late descent)
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< the plan's contact point [m]
  Eigen::Vector3d landed_W = Eigen::Vector3d::Zero();  ///< the simulated contact point at touchdown [m]
  double error_m = 0.0;          ///< |landed - target| in xy [m]
  int stair = -1;                ///< the surface it landed on (-1: off the stairs)
  bool in_step_region = false;   ///< landed inside that surface's step region
};

/// A robot link other than a foot that touched the stairs.
struct LinkContact {
  std::string link;  ///< the URDF link
  std::string stair_geom;    ///< the first stair geom it touched
  double t_first = 0.0;      ///< [s, plan time]
  double max_depth = 0.0;    ///< deepest penetration [m]
  int steps = 0;             ///< simulation steps in contact
};

/// Peak torque of one joint over the run.
struct JointTorquePeak {
  std::string joint;  ///< the URDF joint
  double peak = 0.0;          ///< largest |torque| the controller asked for [N m]
  double effort_limit = 0.0;  ///< the URDF's effort limit [N m]; the motor saturates there
  double ratio = 0.0;         ///< peak / effort_limit
  double t = 0.0;             ///< when [s, plan time]
};

/// The simulated robot at one instant, for drawings: every robot body's world position and its
/// parent (index into `bodies`, -1 for the base), plus foot spheres.
struct SimFrame {
  double t = 0.0;  ///< [s, plan time]
  Eigen::Vector3d base_W = Eigen::Vector3d::Zero();          ///< measured base position [m]
  Eigen::Vector3d base_rpy = Eigen::Vector3d::Zero();        ///< measured roll, pitch, yaw [rad]
  Eigen::Vector3d planned_W = Eigen::Vector3d::Zero();       ///< the plan's base position then [m]
  double planned_pitch = 0.0;                                ///< the plan's pitch then [rad]
  std::vector<bool> stance;                                  ///< per plan leg: stance (true) or swing
  std::vector<std::string> legs;                             ///< the legs of `stance` and `joint_q`
  std::vector<Eigen::Vector3d> joint_q;                      ///< per leg: its three joint angles [rad]
  std::vector<Eigen::Vector3d> bodies;  ///< every robot body's world position [m]
  std::vector<int> parents;  ///< each body's parent: index into `bodies`, -1 for the base
  std::vector<Eigen::Vector3d> feet;  ///< foot sphere centres [m]
  std::vector<double> foot_radii;  ///< foot sphere radii [m]
};

/// How a simulated run of a plan went: the verdict, how well it tracked, contacts, torques, impacts.
struct SimulationOutcome {
  SimStatus status = SimStatus::kStalled;  ///< success, fall or stalled
  std::string cause;               ///< the first cause of a failure; empty on a clean success
  double t_end = 0.0;              ///< plan time at which the run ended [s]
  Eigen::Vector3d final_base_W = Eigen::Vector3d::Zero();  ///< base position at the end [m]
  Eigen::Vector3d final_rpy = Eigen::Vector3d::Zero();  ///< base roll, pitch, yaw at the end [rad]
  double final_error_m = 0.0;      ///< final base position against the plan's last pose [m]
  double max_roll = 0.0;           ///< largest |roll| [rad]
  double max_pitch_error = 0.0;    ///< largest |pitch - planned pitch| [rad]
  double max_height_error = 0.0;   ///< largest |z - planned z| of the base [m]
  std::vector<FootLanding> landings;  ///< every footstep as executed, in time order
  std::vector<LinkContact> other_contacts;  ///< legs (not feet) and the body against the stairs
  std::vector<ImpactRecord> impacts;        ///< every impact detected and the response carried out, in time order
  /// Smallest distance of a robot link other than a foot to the stairs seen over the run [m]
  /// (negative: penetration); the detection margin (MjcfSettings::detect_margin) when none came closer.
  double min_link_clearance_m = 0.0;
  std::string closest_link;        ///< "<link> to <stair geom>" for that distance
  std::vector<JointTorquePeak> torques;  ///< every joint's peak torque
  double max_torque_ratio = 0.0;  ///< largest peak / effort limit over the joints
  /// The plan's own dynamic feasibility at this pace (PlanZmpMargin): the smallest margin of its
  /// zero-moment point inside the support polygon [m] (negative: no stance can carry that motion),
  /// when, and the largest horizontal body acceleration it asks for [m/s^2].
  double plan_zmp_margin_m = 0.0;
  double plan_zmp_t = 0.0;  ///< when the smallest ZMP margin occurs [s, plan time]
  double plan_max_acceleration = 0.0;  ///< largest horizontal body acceleration the plan asks for [m/s^2]
  int force_qp_failures = 0;       ///< control steps whose stance-force QP did not solve (forces zero then)
  /// Where the stance forces came from: StanceForceSource::kWrench or kConvexMpc (kByGait resolved).
  StanceForceSource stance_forces = StanceForceSource::kWrench;
  /// Largest horizontal distance a stance foot moved from where its stance began [m]: slip on the
  /// tread (rolling adds the foot radius times the shank's turn, millimetres). A foot that slides
  /// away unloads its leg and the support polygon with it.
  double max_foot_slip_m = 0.0;
  std::string slipped_leg;         ///< the leg of that largest slip
  double slip_t = 0.0;             ///< when it was reached [s, plan time]
  double time_scale = 1.0;         ///< how many times slower than planned the plan was played
  int sim_steps = 0;  ///< simulation steps taken
  double sim_time_s = 0.0;  ///< simulated time [s]
  double wall_time_s = 0.0;  ///< wall-clock time of the run [s]
  double real_time_factor = 0.0;   ///< simulated seconds per wall-clock second
  std::vector<SimFrame> frames;    ///< when SimSettings::frame_interval > 0

  /// Largest landing error [m].
  double MaxLandingError() const;
  /// Every footstep touched down inside its step region.
  bool AllLandedInRegions() const;
  /// The physics verdict to compare with the validator's: success, every foot in its region and
  /// no link other than a foot on the stairs.
  bool Passed() const;
  /// Passed(), and no link other than a foot ever closer to the stairs than `clearance` (the
  /// validator's margin), so that the two verdicts ask the same question.
  bool PassedWithClearance(double clearance) const;
  /// Why Passed() is false, in a few words ("" when it passed).
  std::string FirstCause() const;
};

}  // namespace stairplan
