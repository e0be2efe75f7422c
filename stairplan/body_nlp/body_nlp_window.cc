// The body NLP's window: its data per knot (neutral body, references, feet's heights, stance rows)
// taken from the planner's schedule, and the constraint screening that picks the bound sides and
// acceleration rows near active at a point, so each round's program holds only those.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "stairplan/body_nlp/body_nlp_internal.h"

namespace stairplan {
namespace body_nlp_detail {

WindowData Prepare(BodyPlanner& planner, double t0, int n) {
  const BodyPlannerSettings& set = planner.settings();
  const FootSchedule& schedule = planner.schedule();
  WindowData d;
  d.planner = &planner;
  d.n = n;
  d.t0 = t0;
  d.heading = schedule.heading();
  d.neutral_x.resize(n);
  d.neutral_y.resize(n);
  d.pitch_ref.resize(n);
  d.shift_ref.resize(n);
  d.foot_z.resize(n * kBodyLegs);
  for (int k = 0; k < n; ++k) {
    const double t = t0 + k * set.knot_dt;
    const Eigen::Vector2d xy = schedule.NeutralBodyXY(t);
    d.neutral_x[k] = xy.x();
    d.neutral_y[k] = xy.y();
    const double feet_pitch = schedule.FeetPitch(t);
    d.pitch_ref[k] = std::clamp(feet_pitch, -set.max_pitch, set.max_pitch);
    const double stairness =
        planner.stairs_pitch() > 0.0 ? std::clamp(std::abs(feet_pitch) / planner.stairs_pitch(), 0.0, 1.0) : 0.0;
    d.shift_ref[k] = set.stairs_com_shift * stairness;
    for (int l = 0; l < kBodyLegs; ++l) {
      const LegPhase phase = schedule.Phase(l, t);
      d.foot_z[k * kBodyLegs + l] = phase.foot_W.z();
      if (k == 0 || !phase.stance) continue;
      const Eigen::Vector3d& c = schedule.footholds()[static_cast<std::size_t>(phase.foothold)].contact_W;
      d.rows.push_back({k, l, phase.foothold, c.x(), c.z()});
    }
  }
  return d;
}

// The acceleration of quantity q over knots k .. k + 2 [per knot^2] and its limit.
double AccelAt(const Eigen::VectorXd& x, int q, int k) { return x[3 * k + q] - 2.0 * x[3 * (k + 1) + q] + x[3 * (k + 2) + q]; }
double AccelLimit(const BodyPlannerSettings& set, int q) {
  const double dt2 = set.knot_dt * set.knot_dt;
  return (q == 0 ? set.max_height_accel : q == 1 ? set.max_pitch_accel : set.max_shift_accel) * dt2;
}

// Adds to `sel` every constraint within `margin` (bounds) or above `fraction` of its limit
// (accelerations) at x; returns how many it added.
int Screen(const WindowData& d, const Eigen::VectorXd& x, double margin, double fraction, Selection* sel) {
  int added = 0;
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    const Eigen::Vector2d m = d.Margins(d.rows[i], x);
    for (int side = 0; side < 2; ++side) {
      if (m[side] < margin && !sel->sides[i][static_cast<std::size_t>(side)]) {
        sel->sides[i][static_cast<std::size_t>(side)] = true;
        ++added;
      }
    }
  }
  const BodyPlannerSettings& set = d.planner->settings();
  for (int q = 0; q < 3; ++q) {
    for (int k = 0; k + 2 < d.n; ++k) {
      const std::size_t row = static_cast<std::size_t>(q * (d.n - 2) + k);
      if (!sel->accel[row] && std::abs(AccelAt(x, q, k)) > fraction * AccelLimit(set, q)) {
        sel->accel[row] = true;
        ++added;
      }
    }
  }
  return added;
}

}  // namespace body_nlp_detail
}  // namespace stairplan
