#include "stairplan/simulation/plan_dynamics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "stairplan/planning/com_model.h"
#include "stairplan/planning/plan_timeline.h"
#include "stairplan/simulation/body_reference.h"

namespace stairplan {
namespace {

double HullCross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Signed distance of p inside the convex hull of `points` (a few feet: monotone chain), positive
// inside; -infinity when the hull is degenerate.
double MarginInHull(std::vector<Eigen::Vector2d> points, const Eigen::Vector2d& p) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower hull
    while (k >= 2 && HullCross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && HullCross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  if (k < 4) return -std::numeric_limits<double>::infinity();  // fewer than three corners
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < k; ++i) {  // counter-clockwise: inside is to the left of each edge
    const Eigen::Vector2d edge = hull[i + 1] - hull[i];
    margin = std::min(margin, HullCross(hull[i], hull[i + 1], p) / edge.norm());
  }
  return margin;
}

}  // namespace

ZmpMargin PlanZmpMargin(const RobotModel& robot, const Plan& plan, double time_scale, double dt, double until) {
  if (!(time_scale > 0.0) || !(dt > 0.0)) throw std::invalid_argument("PlanZmpMargin: time_scale and dt must be positive");
  ZmpMargin worst;
  worst.margin_m = std::numeric_limits<double>::infinity();
  if (plan.body.empty() || plan.initial_feet_W.size() != plan.legs.size()) return worst;
  const Eigen::Vector3d com_B = ApproximateComOffset(robot);
  const double duration = std::min(plan.duration(), until);
  std::vector<Eigen::Vector2d> stance_xy;
  for (double t = 0.0; t <= duration + 1e-9; t += dt) {
    std::vector<bool> in_stance;
    const std::vector<Eigen::Vector3d> feet = FeetAt(plan.legs, plan.initial_feet_W, plan.footsteps, t, &in_stance);
    stance_xy.clear();
    double feet_z = 0.0;
    for (std::size_t i = 0; i < feet.size(); ++i) {
      if (!in_stance[i]) continue;
      stance_xy.push_back(feet[i].head<2>());
      feet_z += feet[i].z();
    }
    if (stance_xy.size() < 3) continue;
    feet_z /= static_cast<double>(stance_xy.size());
    const BodyReferenceState body = BodyReferenceAt(plan.body, t);
    const Eigen::Vector3d com_W = body.pose.ToIsometry() * com_B;
    const Eigen::Vector2d acceleration = body.acceleration_W.head<2>() / (time_scale * time_scale);
    const double height = std::max(com_W.z() - feet_z, 0.0);
    const Eigen::Vector2d zmp = com_W.head<2>() - acceleration * height / 9.81;
    const double margin = MarginInHull(stance_xy, zmp);
    if (!std::isfinite(margin)) continue;
    worst.max_acceleration = std::max(worst.max_acceleration, acceleration.norm());
    if (margin < worst.margin_m) {
      worst.margin_m = margin;
      worst.t = t;
    }
  }
  if (!std::isfinite(worst.margin_m)) worst.margin_m = 0.0;
  return worst;
}

}  // namespace stairplan
