// The feet's timeline from a footstep plan: for every leg, alternating stances on footholds and
// swings between them, queried at any time without allocating. The body planner reads from it
// which legs stand where at each knot, the feet's mean height and slope, and the neutral body x
// (the body above the feet's centre, as the crawl planner carries it).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

/// One place a foot stands: the leg, its contact point on a surface and that surface.
struct Foothold {
  int leg = -1;                                          ///< index in the robot's legs
  Eigen::Vector3d contact_W = Eigen::Vector3d::Zero();  ///< contact point [m]
  int stair = -1;                                        ///< surface index, -1 when unknown
};

/// A leg at one instant.
struct LegPhase {
  bool stance = true;  ///< in stance (false: swinging)
  int foothold = -1;       ///< standing on (stance) or leaving (swing)
  int next_foothold = -1;  ///< the next foothold (the target during a swing), -1 after the last
  double progress = 0.0;   ///< swing progress in [0, 1]; 0 in stance
  double t_liftoff = 0.0;  ///< the phase's liftoff (swing) or the next liftoff (stance; +inf if none)
  double t_touchdown = 0.0;  ///< the phase's touchdown (swing) or the last one (stance)
  /// Contact point; in swing the straight line between the footholds (the neutral body follows
  /// it), while FootSchedule::SwingFoot() gives where the foot really is.
  Eigen::Vector3d foot_W = Eigen::Vector3d::Zero();
  int swing = -1;          ///< in swing: the leg's swing number (for SwingFoot()), else -1
};

/// The feet's timeline of a footstep plan: each leg's stances and swings, queried allocation-free.
class FootSchedule {
 public:
  FootSchedule() = default;
  /// Reads `plan`'s initial feet and footsteps for `robot` (legs matched by name); swings follow
  /// SwingTrajectory with `swing` settings and each footstep's apex (from `stairs` where the
  /// footstep states none; without stairs, min_lift above the higher foothold). Throws
  /// std::invalid_argument naming the footstep when a leg is unknown, times are not finite or a
  /// leg's footsteps overlap in time.
  FootSchedule(const RobotModel& robot, const Plan& plan, const Staircase* stairs = nullptr,
               const SwingSettings& swing = {});

  /// Every foothold of the plan (the initial ones included).
  const std::vector<Foothold>& footholds() const { return footholds_; }
  /// Number of legs.
  int leg_count() const { return static_cast<int>(legs_.size()); }
  /// When the last swing ends [s].
  double end_time() const { return end_time_; }
  ///@{
  /// Body yaw (0 facing forward, pi facing backward) and its cosine along x (+1 or -1).
  double yaw() const { return yaw_; }
  double heading() const { return heading_; }
  ///@}

  /// Leg `leg` at time t (clamped to [0, end_time()]). Allocation-free.
  LegPhase Phase(int leg, double t) const;
  /// Where leg `leg`'s foot contact point is in `phase` (from Phase()): on its foothold in stance,
  /// along its swing trajectory in swing. Allocation-free.
  Eigen::Vector3d SwingFoot(int leg, const LegPhase& phase) const;
  /// The body above the feet at t: the mean of (foot - the leg's neutral offset), feet in swing
  /// on the straight line between their footholds. It moves only while a foot swings, so its
  /// velocity steps at every liftoff and touchdown.
  Eigen::Vector2d FeetCentreXY(double t) const;
  /// The body's neutral horizontal position at t: FeetCentreXY averaged over smoothing_window()
  /// centred at t. Each swing's ramp becomes an S-curve: the velocity steps become accelerations
  /// of the ramp's velocity over the window (about 0.4 m/s^2 on the default crawl), and the neutral body
  /// stays within an eighth of the window's travel of the feet centre. The body planner's weight
  /// shifts are measured from it, so their acceleration limits bound the body's.
  Eigen::Vector2d NeutralBodyXY(double t) const;
  /// The median swing duration [s]; 0 without swings.
  double smoothing_window() const { return smoothing_window_; }
  /// The pitch of the line from the hind feet to the front feet at t (nose-up negative).
  double FeetPitch(double t) const;
  /// The same from the legs' phases at one instant (leg_count() of them, in leg order, as Phase()
  /// gives them), for callers that have the phases already.
  double FeetPitch(const LegPhase* phases) const;
  /// The leg's neutral foot offset from the body origin in the world, horizontal [m].
  const Eigen::Vector2d& NeutralOffset(int leg) const { return legs_[static_cast<std::size_t>(leg)].offset_W; }
  /// True for a front leg.
  bool IsFront(int leg) const { return legs_[static_cast<std::size_t>(leg)].front; }

 private:
  struct LegTimeline {
    Eigen::Vector2d offset_W = Eigen::Vector2d::Zero();
    bool front = false;
    std::vector<int> footholds;     // in time order; footholds[0] is the initial one
    std::vector<double> liftoffs;   // liftoffs[j]: leaving footholds[j]
    std::vector<double> touchdowns; // touchdowns[j]: arriving on footholds[j + 1]
    std::vector<SwingTrajectory> swings;  // swings[j]: from footholds[j] to footholds[j + 1]
    // The integral of the foot's horizontal contact point over time from t = 0 (feet in swing on
    // the straight line), at each liftoff and touchdown: FootIntegral() reads it.
    std::vector<Eigen::Vector2d> integral_at_liftoff, integral_at_touchdown;
  };
  // Fills the legs' integrals and smoothing_window_ once the footsteps are read.
  void PrepareNeutral();
  // The integral from 0 to t of leg `leg`'s horizontal contact point (negative before 0).
  Eigen::Vector2d FootIntegral(int leg, double t) const;
  // Leg `leg`'s j-th foothold, horizontal.
  Eigen::Vector2d FootholdXY(int leg, std::size_t j) const;
  // FeetPitch over the feet foot_W(leg) gives.
  template <typename FootAt>
  double FeetPitchOf(const FootAt& foot_W) const;

  std::vector<Foothold> footholds_;
  std::vector<LegTimeline> legs_;
  double end_time_ = 0.0;
  double smoothing_window_ = 0.0;
  double yaw_ = 0.0;
  double heading_ = 1.0;
};

}  // namespace stairplan
