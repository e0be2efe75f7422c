#include "stairplan/planning/validation/body_rates.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "stairplan/planning/plan_timeline.h"

namespace stairplan {
namespace {

// pitch'' and yaw'' at sample i (0 < i < size - 1), the same second difference as the position's.
Eigen::Vector2d AngleAccelerationAt(const std::vector<BodyState>& body, std::size_t i) {
  const BodyState &a = body[i - 1], &b = body[i], &c = body[i + 1];
  const double dt0 = b.t - a.t, dt1 = c.t - b.t;
  if (dt0 < 1e-9 || dt1 < 1e-9) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d q0(a.pitch, a.yaw), q1(b.pitch, b.yaw), q2(c.pitch, c.yaw);
  return ((q2 - q1) / dt1 - (q1 - q0) / dt0) / (0.5 * (dt0 + dt1));
}

BodyRates RatesAtSample(const std::vector<BodyState>& body, std::size_t i) {
  BodyRates rates;
  if (i == 0 || i + 1 >= body.size()) return rates;
  rates.linear_W = BodyAccelerationAt(body, i);
  const Eigen::Vector2d angles = AngleAccelerationAt(body, i);
  const Eigen::Vector3d pitch_axis_W = Eigen::AngleAxisd(body[i].yaw, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitY();
  rates.angular_W = angles.x() * pitch_axis_W + angles.y() * Eigen::Vector3d::UnitZ();
  return rates;
}

}  // namespace

BodyRates BodyRatesAt(const std::vector<BodyState>& body, double t) {
  if (body.size() < 3) return {};
  const auto next = std::upper_bound(body.begin(), body.end(), t, [](double v, const BodyState& b) { return v < b.t; });
  if (next == body.begin()) return RatesAtSample(body, 0);
  if (next == body.end()) return RatesAtSample(body, body.size() - 1);
  const auto i1 = static_cast<std::size_t>(next - body.begin());
  const std::size_t i0 = i1 - 1;
  const double span = body[i1].t - body[i0].t;
  const double u = span > 1e-12 ? std::clamp((t - body[i0].t) / span, 0.0, 1.0) : 0.0;
  const BodyRates a = RatesAtSample(body, i0), b = RatesAtSample(body, i1);
  return {a.linear_W + u * (b.linear_W - a.linear_W), a.angular_W + u * (b.angular_W - a.angular_W)};
}

}  // namespace stairplan
