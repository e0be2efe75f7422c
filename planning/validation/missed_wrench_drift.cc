#include "planning/validation/missed_wrench_drift.h"

namespace stairplan {

void MissedWrenchDrift::Reset() {
  started_ = false;
  speed_ = drift_ = duration_ = 0.0;
}

double MissedWrenchDrift::Update(double t, double residual) {
  const double dt = started_ && t > last_t_ ? t - last_t_ : 0.0;
  started_ = true;
  last_t_ = t;
  if (!(residual > floor_)) {
    speed_ = drift_ = duration_ = 0.0;
    return drift_;
  }
  // Semi-implicit Euler over the step that ends here, at this instant's miss.
  speed_ += residual / mass_ * dt;
  drift_ += speed_ * dt;
  duration_ += dt;
  return drift_;
}

}  // namespace stairplan
