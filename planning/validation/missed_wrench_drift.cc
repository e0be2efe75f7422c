#include "planning/validation/missed_wrench_drift.h"

namespace stairplan {

void MissedWrenchDrift::Reset() {
  started_ = false;
  speed_ = drift_ = duration_ = 0.0;
}

double MissedWrenchDrift::Update(double t, double residual) {
  const double dt = started_ && t > last_t_ ? t - last_t_ : 0.0;
  const double previous = started_ ? last_residual_ : 0.0;
  started_ = true;
  last_t_ = t;
  last_residual_ = residual;
  if (!(residual > floor_)) {
    speed_ = drift_ = duration_ = 0.0;
    return drift_;
  }
  // The miss varies linearly over the step that ends here (from the last instant's, which may be
  // below the floor): exact for that, as the instants are 20 ms apart or less.
  const double a0 = previous / mass_, a1 = residual / mass_;
  drift_ += speed_ * dt + (a0 / 3.0 + a1 / 6.0) * dt * dt;
  speed_ += 0.5 * (a0 + a1) * dt;
  duration_ += dt;
  return drift_;
}

}  // namespace stairplan
