#include "stairplan/planning/plan_timeline.h"

#include <algorithm>
#include <cmath>

#include "stairplan/planning/swing_trajectory.h"

namespace stairplan {

std::vector<Eigen::Vector3d> FeetAt(const std::vector<std::string>& legs, const std::vector<Eigen::Vector3d>& initial,
                                    const std::vector<Footstep>& footsteps, double t, std::vector<bool>* in_stance) {
  const auto straight = [](const Footstep& f, double phase) -> Eigen::Vector3d {
    return f.from_W + phase * (f.position_W - f.from_W);
  };
  return FeetWhileSwinging(legs, initial, footsteps, t, straight, in_stance);
}

BodyPose BodyPoseAt(const std::vector<BodyState>& body, double t) {
  BodyPose pose;
  if (body.empty()) return pose;
  const auto next = std::upper_bound(body.begin(), body.end(), t, [](double v, const BodyState& b) { return v < b.t; });
  const BodyState& a = next == body.begin() ? body.front() : *(next - 1);
  const BodyState& b = next == body.end() ? body.back() : *next;
  const double u = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
  pose.position_W = {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.z + u * (b.z - a.z)};
  pose.pitch = a.pitch + u * (b.pitch - a.pitch);
  pose.yaw = a.yaw + u * (b.yaw - a.yaw);
  return pose;
}

Eigen::Vector3d BodyAccelerationAt(const std::vector<BodyState>& body, std::size_t i) {
  const BodyState &a = body[i - 1], &b = body[i], &c = body[i + 1];
  const double dt0 = b.t - a.t, dt1 = c.t - b.t;
  if (dt0 < 1e-9 || dt1 < 1e-9) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d p0(a.x, a.y, a.z), p1(b.x, b.y, b.z), p2(c.x, c.y, c.z);
  return ((p2 - p1) / dt1 - (p1 - p0) / dt0) / (0.5 * (dt0 + dt1));
}

double PeakBodyAcceleration(const std::vector<BodyState>& body) {
  double peak = 0.0;
  for (std::size_t i = 1; i + 1 < body.size(); ++i) peak = std::max(peak, BodyAccelerationAt(body, i).cwiseAbs().maxCoeff());
  return peak;
}

double FlightDuration(const Plan& plan) {
  if (plan.footsteps.empty()) return 0.0;
  double first = plan.footsteps.front().t_liftoff, last = plan.footsteps.front().t_touchdown;
  for (const Footstep& f : plan.footsteps) {
    first = std::min(first, f.t_liftoff);
    last = std::max(last, f.t_touchdown);
  }
  return last - first;
}

double TravelSpeed(const Plan& plan) {
  const double flight = FlightDuration(plan);
  if (plan.body.empty() || !(flight > 0.0)) return 0.0;
  const BodyState &a = plan.body.front(), &b = plan.body.back();
  return std::hypot(b.x - a.x, b.y - a.y) / flight;
}

}  // namespace stairplan
