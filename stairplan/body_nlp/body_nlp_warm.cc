// The body NLP's warm start in a loop: a previous window's solution shifted to the next window's
// time (knots interpolated or extrapolated, multipliers from the nearest previous knot) with the
// measured state blended in within the acceleration limits.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "stairplan/body_nlp/body_nlp.h"
#include "stairplan/body_nlp/body_nlp_internal.h"

namespace stairplan {
namespace {

BodyState Lerp(const BodyState& a, const BodyState& b, double f) {
  const auto mix = [f](double u, double v) { return u + f * (v - u); };
  BodyState s;
  s.t = mix(a.t, b.t);
  s.x = mix(a.x, b.x);
  s.y = mix(a.y, b.y);
  s.z = mix(a.z, b.z);
  s.pitch = mix(a.pitch, b.pitch);
  s.yaw = mix(a.yaw, b.yaw);
  s.com_shift = mix(a.com_shift, b.com_shift);
  s.com_shift_y = mix(a.com_shift_y, b.com_shift_y);
  return s;
}

// Moves knot 0 of `knots` to `state` and fades the difference out over the next knots, (1 - k/m)^2
// for k < m, with m long enough that the fade's acceleration 2 |delta| / m^2 is half the limit:
// a guess whose knot 0 alone jumps breaks the acceleration limits at the start (the state a loop
// measures is rarely where the previous plan put it), and Ipopt then crawls out of that corner
// in short steps.
void BlendInState(const BodyState& state, const Eigen::Vector3d& accel_limits, std::vector<BodyState>* knots) {
  const int n = static_cast<int>(knots->size());
  BodyState& first = knots->front();
  const Eigen::Vector3d delta(state.z - first.z, state.pitch - first.pitch, state.com_shift - first.com_shift);
  const double t0 = first.t;
  first = state;
  first.t = t0;
  for (int q = 0; q < 3; ++q) {
    const double m = std::clamp(std::ceil(std::sqrt(4.0 * std::abs(delta[q]) / accel_limits[q])), 1.0, n - 1.0);
    for (int k = 1; k < m; ++k) {
      const double w = (1.0 - k / m) * (1.0 - k / m);
      BodyState& b = (*knots)[static_cast<std::size_t>(k)];
      (q == 0 ? b.z : q == 1 ? b.pitch : b.com_shift) += w * delta[q];
    }
  }
}

void CheckSolution(const BodyNlpSolution& s) {
  const std::size_t n = s.knots.size();
  if (n < 3) throw std::invalid_argument("BodyNlpSolution::knots: needs at least 3 knots");
  const auto sized = [](std::size_t got, std::size_t want, const char* field) {
    if (got != want) {
      throw std::invalid_argument(std::string("BodyNlpSolution::") + field + ": " + std::to_string(got) +
                                  " entries, the knots need " + std::to_string(want));
    }
  };
  sized(s.stance_foothold.size(), n * kBodyLegs, "stance_foothold");
  sized(s.stance_duals.size(), n * kBodyLegs, "stance_duals");
  sized(s.accel_duals.size(), 3 * (n - 2), "accel_duals");
  sized(s.bound_duals.size(), 3 * n, "bound_duals");
}

}  // namespace

using body_nlp_detail::AccelLimit;

BodyNlpSolution ShiftBodyNlpSolution(const BodyNlpSolution& previous, double t0, const BodyPlannerSettings& settings,
                                     const BodyState& state) {
  CheckSolution(previous);
  const double knot_dt = settings.knot_dt;
  const Eigen::Vector3d accel_limits(AccelLimit(settings, 0), AccelLimit(settings, 1), AccelLimit(settings, 2));
  // Half a microsecond of slack: a loop adding its period to t0 rounds.
  if (!(t0 >= previous.t0 - 5e-7)) throw std::invalid_argument("t0: before the previous solution's t0");
  const int n = static_cast<int>(previous.knots.size());
  const double shift = std::max(0.0, (t0 - previous.t0) / knot_dt);  // in previous knots
  BodyNlpSolution s;
  s.t0 = t0;
  s.knots.resize(static_cast<std::size_t>(n));
  s.stance_foothold.assign(static_cast<std::size_t>(n * kBodyLegs), -1);
  s.stance_duals.assign(static_cast<std::size_t>(n * kBodyLegs), {0.0, 0.0});
  s.accel_duals.assign(static_cast<std::size_t>(3 * (n - 2)), 0.0);
  s.bound_duals.assign(static_cast<std::size_t>(3 * n), 0.0);
  for (int k = 0; k < n; ++k) {
    // Knot k of the new window is at previous knot k + shift: the point interpolated there, or
    // beyond the end extrapolated from the last two knots (holding the last knot instead made a
    // velocity kink whose acceleration row Ipopt first had to leave: 3.75 iterations instead of 3.25
    // on average in the bench); the multipliers of the previous knot nearest to it.
    const double at = k + shift;
    const int segment = std::min(static_cast<int>(std::floor(at)), n - 2);
    BodyState& knot = s.knots[static_cast<std::size_t>(k)];
    knot = Lerp(previous.knots[static_cast<std::size_t>(segment)], previous.knots[static_cast<std::size_t>(segment + 1)],
                at - segment);
    knot.pitch = std::clamp(knot.pitch, -settings.max_pitch, settings.max_pitch);
    knot.com_shift = std::clamp(knot.com_shift, -settings.max_shift, settings.max_shift);
    knot.t = t0 + k * knot_dt;
    const int nearest = static_cast<int>(std::lround(at));
    if (nearest > n - 1) continue;  // a knot the previous window did not reach: multipliers 0
    const auto at_index = [](int i) { return static_cast<std::size_t>(i); };
    for (int l = 0; l < kBodyLegs; ++l) {
      s.stance_foothold[at_index(k * kBodyLegs + l)] = previous.stance_foothold[at_index(nearest * kBodyLegs + l)];
      s.stance_duals[at_index(k * kBodyLegs + l)] = previous.stance_duals[at_index(nearest * kBodyLegs + l)];
    }
    for (int i = 0; i < 3; ++i) s.bound_duals[at_index(3 * k + i)] = previous.bound_duals[at_index(3 * nearest + i)];
    if (k + 2 < n && nearest + 2 < n) {
      for (int q = 0; q < 3; ++q) {
        s.accel_duals[at_index(q * (n - 2) + k)] = previous.accel_duals[at_index(q * (n - 2) + nearest)];
      }
    }
  }
  BlendInState(state, accel_limits, &s.knots);
  return s;
}

}  // namespace stairplan
