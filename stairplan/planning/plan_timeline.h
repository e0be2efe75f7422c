// A plan sampled in time: where the feet and the body are at any instant, and how hard the body
// accelerates. The judges (the validator, the dynamics check, the executor) and the planners read
// plans through these, so all of them see the same motion between samples.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stairplan/kinematics/body_pose.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// Where each foot is at time t (contact points, legs in `legs` order), swing feet interpolated.
std::vector<Eigen::Vector3d> FeetAt(const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& initial,
                                    const std::vector<Footstep>& footsteps, double t, std::vector<bool>* in_stance = nullptr);

/// The body pose at time t, interpolated linearly between body samples.
BodyPose BodyPoseAt(const std::vector<BodyState>& body, double t);

/// The acceleration of the body's position at sample i (0 < i < size - 1), by finite differences
/// over its neighbours [m/s^2]; zero where two samples share a time.
Eigen::Vector3d BodyAccelerationAt(const std::vector<BodyState>& body, std::size_t i);

/// The largest component of BodyAccelerationAt over all samples [m/s^2]: what a robot executing
/// the plan must produce; 0 for fewer than three samples.
double PeakBodyAcceleration(const std::vector<BodyState>& body);

/// From the first liftoff to the last touchdown [s]; 0 without footsteps.
double FlightDuration(const Plan& plan);

/// The body's advance along the travel (horizontal, from its first sample to its last) over
/// FlightDuration() [m/s]; 0 without footsteps or body.
double TravelSpeed(const Plan& plan);

}  // namespace stairplan
