// The drift a missed wrench adds up to (planning/validation/missed_wrench_drift.h): the body's
// position error under the missing acceleration, integrated exactly for a miss that varies
// linearly between instants, and forgotten where the feet give what is asked again.
#include <catch2/catch.hpp>

#include "planning/validation/missed_wrench_drift.h"

using namespace stairplan;

TEST_CASE("a steady miss drifts the body by half its acceleration times the time squared", "[drift]") {
  constexpr double kBodyMass = 20.0, kMiss = 40.0;  // 2 m/s^2 missing
  MissedWrenchDrift drift(kBodyMass, 1.0);
  CHECK(drift.Update(0.0, 0.0) == 0.0);
  // The miss ramps up over the first 20 ms, then holds for 0.3 s.
  double t = 0.0;
  for (int k = 1; k <= 16; ++k) drift.Update(t = 0.02 * k, kMiss);
  const double ramp = 0.02, held = t - ramp;
  const double a = kMiss / kBodyMass;
  // Over the ramp: a t^3 / (6 ramp) and speed a ramp / 2; then steady.
  const double expected = a * ramp * ramp / 6.0 + 0.5 * a * ramp * held + 0.5 * a * held * held;
  CHECK(drift.drift() == Approx(expected).epsilon(1e-9));
  CHECK(drift.duration() == Approx(t));
  // Irregular instants integrate the same motion.
  MissedWrenchDrift uneven(kBodyMass, 1.0);
  uneven.Update(0.0, 0.0);
  uneven.Update(0.02, kMiss);
  for (double s : {0.05, 0.07, 0.11, 0.2, 0.23, 0.32}) uneven.Update(s, kMiss);
  CHECK(uneven.drift() == Approx(expected).epsilon(1e-9));
}

TEST_CASE("a miss at or below the floor ends the stretch, and Reset forgets it", "[drift]") {
  MissedWrenchDrift drift(10.0, 5.0);
  drift.Update(0.0, 50.0);
  drift.Update(0.1, 50.0);
  CHECK(drift.drift() > 0.0);
  CHECK(drift.Update(0.12, 5.0) == 0.0);
  CHECK(drift.duration() == 0.0);
  drift.Update(0.2, 50.0);
  CHECK(drift.drift() > 0.0);
  drift.Reset();
  CHECK(drift.drift() == 0.0);
  // After a reset the first instant has no step behind it.
  CHECK(drift.Update(5.0, 50.0) == 0.0);
}
