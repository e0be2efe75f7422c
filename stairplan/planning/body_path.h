// A quasi-static body path for a given footstep sequence: while a leg swings, the centre of mass
// sits over the centroid of the three stance feet (so it stays inside the support triangle);
// with four feet down it moves to the next triangle; the body rides at a fixed hip height above
// the feet, pitched along the line from the hind to the front feet. Planners that choose
// footsteps (the crawl, the step planner) use it for their first body path.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/body_pose.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/com_model.h"
#include "stairplan/planning/plan.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

/// How the quasi-static body path is laid over a crawl's footsteps.
struct BodyPathSettings {
  /// Hip above the feet, as a fraction of the leg's reach: 0.6 leaves the legs room to pitch with
  /// the flight and to lift the swing foot over a nosing (0.75 overextends stairbot's front legs).
  double hip_height_fraction = 0.6;
  double sample_period = 0.05;        ///< sampling of the body trajectory [s]
  /// How far toward the support triangle's centroid the COM moves while a leg swings (1: all the way).
  double stability_shift = 1.0;
  /// Share of the feet's slope (hind to front) the body pitches by; less keeps legs upright.
  double pitch_fraction = 0.75;
  /// Correct the body so the COM computed through each leg's IK (not the lumped estimate) sits
  /// where the support polygon wants it; this many fixed-point passes per sample (0: off).
  int com_passes = 2;
  /// With the stairs known, the body is moved into the range of heights at which the stance (swing
  /// feet on their swings) passes the stance check: IK within limits, leg clearance above this, at
  /// least `height_margin` inside it. One correction holds through each swing (checked at its
  /// liftoff, touchdown and every height_key_period); it changes, eased, while four feet are down
  /// (stairplan/planning/posture_fit.h). Negative: off.
  double touchdown_clearance = 0.005;
  double height_margin = 0.01;  ///< the body stays this far inside the passing height range [m]
  /// The height is kept at least this share of the feasible range away from either end of it, so
  /// the clearance between the instants checked is not left to chance (0: only height_margin).
  double height_centering = 0.3;
  /// Through a swing, the posture is checked this often besides its liftoff and touchdown [s].
  double height_key_period = 0.1;
  /// Also check each swing where its foot ends its rise and starts to lower (SwingSettings'
  /// lift_fraction and lower_fraction), the instants that fold and stretch the leg most. Off by
  /// default: the fit then refuses some swings the default plans are valid with.
  bool check_swing_corners = false;
  /// A feasible height range narrower than this with the body where the previous swing had it
  /// makes the fit try other shifts along the flight, in shift_step up to max_shift either way, as
  /// long as the COM target stays shift_margin inside the support polygon [m].
  double wide_height_range = 0.06;
  double max_shift = 0.09;  ///< largest shift tried either way [m]
  double shift_step = 0.03;  ///< spacing of the shifts tried [m]
  double shift_margin = 0.04;  ///< the COM target stays this far inside the support polygon [m]
  /// When no one eased height suits a whole swing, its height eases through a chain of its
  /// checked instants, no ease faster than this at its peak [m/s^2]: a quarter of the
  /// validator's 2 g, as the stance feet carry the body (a downward 1 g would unload them).
  double max_height_acceleration = 4.9;
  /// The swings the footsteps follow (as the validator replays them).
  SwingSettings swing;

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// The body states for `footsteps` (sorted by touchdown) starting from `initial_feet`, facing `yaw`.
std::vector<BodyState> BodyPathForFootsteps(const RobotModel& robot, const std::vector<std::string>& legs,
                                            const std::vector<Eigen::Vector3d>& initial_feet,
                                            const std::vector<Footstep>& footsteps, double yaw,
                                            const BodyPathSettings& settings = {}, const Staircase* stairs = nullptr);

}  // namespace stairplan
