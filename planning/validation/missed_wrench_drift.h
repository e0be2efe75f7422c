// How far a robot drifts from its plan while its feet miss the plan's wrench. A miss is an
// acceleration the body does not get (residual / mass); integrated twice over a stretch of missed
// instants it is the position error the controller must absorb. A miss for a few milliseconds
// where a pitch ramp stops is millimetres; a crawl at twice its pace, or on a slippery tread,
// misses for whole shifts and drifts centimetres. A stretch ends where the miss falls below the
// floor (the feet can give what is asked again, and the controller recovers).
#pragma once

namespace stairplan {

/// The drift of the current stretch of missed instants, updated instant by instant.
class MissedWrenchDrift {
 public:
  /// `mass` [kg]; a residual at or below `floor` [N] ends a stretch.
  MissedWrenchDrift(double mass, double floor) : mass_(mass), floor_(floor) {}

  /// Forgets the stretch (a new plan).
  void Reset();
  /// The residual [N] at time t (called in time order); returns the stretch's drift [m].
  double Update(double t, double residual);

  double drift() const { return drift_; }        ///< [m]
  double duration() const { return duration_; }  ///< of the current stretch [s]

 private:
  double mass_ = 0.0;
  double floor_ = 0.0;
  bool started_ = false;
  double last_t_ = 0.0;
  double last_residual_ = 0.0;  // [N]
  double speed_ = 0.0;  // [m/s]
  double drift_ = 0.0;
  double duration_ = 0.0;
};

}  // namespace stairplan
