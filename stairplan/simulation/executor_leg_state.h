// The executor's state of one leg (PlanExecutor's private part, shared by the files that carry out
// its concepts: control and phases, impact detection, impact responses).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "stairplan/simulation/plan_executor.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

struct PlanExecutor::LegState {
  int kin = 0;                              // index in kinematics_
  std::string name;
  std::array<int, 3> qpos{}, dof{}, motor{};
  std::array<double, 3> effort{};
  int foot_body = -1;
  int foot_geom = -1;                       // the foot's sphere geom, -1 when it has none
  int knee_body = -1;                       // the body whose origin is the knee joint
  int hip_body = -1;                        // ... the hip joint
  double foot_radius = 0.0;
  Eigen::Vector3d contact_F = Eigen::Vector3d::Zero();  // a foot without a sphere geom: its contact sphere's centre in the foot frame
  bool stance = true;
  Eigen::Vector3d foothold_W = Eigen::Vector3d::Zero();  // where the stance foot stands
  bool stance_measured = false;             // stance_start_W holds where this stance began
  Eigen::Vector3d stance_start_W = Eigen::Vector3d::Zero();
  int step = -1;                            // the footstep being swung, -1 in stance
  int next = 0;                             // next entry of leg_steps_
  std::unique_ptr<SwingTrajectory> swing;
  Eigen::Vector3d q_target = Eigen::Vector3d::Zero();
  Eigen::Vector3d q_target_prev = Eigen::Vector3d::Zero();
  Eigen::Vector3d qd_target_prev = Eigen::Vector3d::Zero();
  bool has_target = false;
  double t_switch = -1e9;                   // plan time of the last liftoff or touchdown [s]
  double swing_t0 = 0.0, swing_t1 = 1.0;    // the swing's timing; a response re-times it [s, plan time]
  double swing_apex = 0.0;                  // the current swing's apex height [m]
  Eigen::Vector3d swing_target_W = Eigen::Vector3d::Zero();
  std::optional<ImpactKind> foot_impact;    // this step's classification of the foot's external force
  double foot_force = 0.0;                  // its magnitude [N]
  double t_first_contact = -1.0;            // the contact list's start of this swing's latest contact [s]
  bool link_touching = false;               // any link of this leg touches the stairs in the contact list
  bool was_touching = false;                // ... did at the previous step
  double t_recorded = -1e9;                 // the last impact recorded in this swing [s]
  double t_responded = -1e9;                // the last response carried out in this swing [s]
  bool scuffed = false;                     // a liftoff scuff was recorded in this swing
  int responses = 0;                        // responses in this swing
};

}  // namespace stairplan
