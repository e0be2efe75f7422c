// Where the body may be for a stance leg: the range of the leg's hip height above its contact
// point, from the leg's reach (feet keep contact, joints within limits) and from collisions (no
// leg link touches the stairs). The body QP asks for it once per stance leg and knot, over the
// small box of fore-aft hip offsets and pitches the cycle's trust region allows. Implementations:
// KinematicBodyBounds (KDL IK and FCL clearances, cached per leg and per foothold); tests use fakes.
#pragma once

#include <vector>

#include "stairplan/planning/body/foot_schedule.h"

namespace stairplan {

/// A box of hip placements relative to one foothold.
struct HipBox {
  int leg = -1;  ///< the stance leg (kinematics order)
  int foothold = -1;       ///< index into the footholds given to SetFootholds()
  double dx_lo = 0.0;      ///< hip minus contact along the body's heading, lowest [m]
  double dx_hi = 0.0;      ///< ... highest [m]
  double pitch_lo = 0.0;   ///< [rad]
  double pitch_hi = 0.0;   ///< [rad]
};

/// Hip height above the contact point [m]; empty when lo > hi.
struct HeightRange {
  double lo = 0.0;  ///< lowest hip height [m]
  double hi = 0.0;  ///< highest hip height [m]
  /// True when no height is valid (lo > hi, or NaN).
  bool empty() const { return !(lo <= hi); }
};

/// Where the body may be for a stance leg: the hip heights the leg allows over a box of placements.
class BodyBounds {
 public:
  virtual ~BodyBounds() = default;
  /// Installs the footholds queries refer to (may allocate and precompute; not per cycle).
  virtual void SetFootholds(const std::vector<Foothold>& footholds) = 0;
  /// The hip heights valid for every placement in `box` (worst case over the box). Allocation-free
  /// once the footholds are set; may compute and cache what it has not seen before.
  virtual HeightRange HipHeight(const HipBox& box) = 0;
  /// The hip heights above a foot point at which the leg reaches it within its joint limits, for
  /// every placement in `box` (box.foothold is not used): the bound of a swinging leg, whose foot
  /// is in the air. Unbounded unless an implementation knows the legs.
  virtual HeightRange ReachHeight(const HipBox& box) {
    (void)box;
    return {-1e9, 1e9};
  }
  /// The hip height above the contacts the body should keep when nothing else matters [m].
  virtual double NominalHipHeight() const = 0;
};

}  // namespace stairplan
