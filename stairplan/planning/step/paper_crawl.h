// The 2012 paper's crawl as a footstep source (Chen, Ko, Li, Lin 2012, "Stair Climbing in a
// Quadruped Robot", "Trajectory planning procedure"): the gait design of stairplan/planning/gait/ laid on a
// real staircase. Right feet land a_min from each nose, left feet a_max (case 1; the front pair
// switched in case 2); each leg lifts off when its hip, moving at a constant speed along the line d
// above the stairs' edges, reaches the point where it is equidistant from its two contacts (eq.
// (3)), and swings for D_i (eqs. (5)-(7)), low under its hip to the riser first, then up and over
// (Footstep::swing_approach_share), as the paper's leg rotates about its hip. On the landings the
// same pattern continues with virtual noses one run apart.
//
// The body is not the paper's rigid constant-velocity line (it would put the hind hips under the
// bottom landing at the start and has no way off the flight): it is the quasi-static body path
// (stairplan/planning/body_path.h) over these footsteps, fitted to the stairs.
#pragma once

#include "stairplan/geometry/constrained_map.h"
#include "stairplan/geometry/staircase.h"
#include "stairplan/kinematics/robot_model.h"
#include "stairplan/planning/body_path.h"
#include "stairplan/planning/gait/crawl_stability.h"
#include "stairplan/planning/plan.h"

namespace stairplan {

/// The paper crawl's robot, design choices, timing and body path.
struct PaperCrawlSettings {
  /// The body path the paper's crawl is planned with: taller hips and lower swings than the pipeline's.
  static BodyPathSettings PaperBody() {
    BodyPathSettings body;
    body.hip_height_fraction = 0.8;
    body.swing.clearance = 0.02;
    body.swing.min_lift = 0.02;
    return body;
  }

  double max_leg_length = 0.21;  ///< l_max, hip to foot [m] (the paper's robot)
  double buffer = 0.42;          ///< p
  /// d [m]. Negative (the default): the d that centres the two contact offsets on the tread,
  /// a_min + a_max = W (4.7 cm on 27 x 17 cm stairs: feet 10.1 and 16.9 cm behind the nose). The
  /// paper's simulation's d = H / 2 would put the right feet 2.9 cm from the nose, in the band the
  /// map keeps free; its error analysis's 2.8 cm the left feet 20.4 cm back, past the step region.
  double hip_clearance = -1.0;
  CrawlCase arrangement = CrawlCase::kRightFirst;  ///< case 1 or case 2 of the contact offsets
  /// How long a swing takes [s]; it sets the hip speed, D_i / swing_duration.
  double swing_duration = 0.5;
  /// Four feet down before the first swing [s].
  double settle_s = 0.5;
  /// The body path over the footsteps. Its swings clear the nose by 2 cm, not the pipeline's
  /// 6 cm: with 21 cm legs on 17 cm risers the paper's swing passes close to the nose (its hip
  /// stays only d above the edges), and a 6 cm clearance would lift the foot above the hip.
  BodyPathSettings body = PaperBody();

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// Plans a climb of `stairs` (direction up, facing forward) with the paper's crawl for a robot
/// with one leg at each corner named LF, RF, LH, RH. Infeasible (status and reason, no throw) when
/// the design fails one of its conditions on these stairs, or a landing is too short.
Plan PlanPaperCrawl(const RobotModel& robot, const Staircase& stairs, const ConstrainedMap& map,
                    const PaperCrawlSettings& settings = {});

}  // namespace stairplan
