#include "stairplan/simulation/body_reference.h"

#include <algorithm>

namespace stairplan {
namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;

Vector5d Values(const BodyState& b) { return (Vector5d() << b.x, b.y, b.z, b.pitch, b.yaw).finished(); }

// Catmull-Rom tangent at sample k (zero at the ends: the plan starts and ends standing).
Vector5d Tangent(const std::vector<BodyState>& body, std::size_t k) {
  if (k == 0 || k + 1 >= body.size()) return Vector5d::Zero();
  const double dt = body[k + 1].t - body[k - 1].t;
  return dt > 0.0 ? Vector5d((Values(body[k + 1]) - Values(body[k - 1])) / dt) : Vector5d::Zero();
}

}  // namespace

BodyReferenceState BodyReferenceAt(const std::vector<BodyState>& body, double t) {
  BodyReferenceState out;
  if (body.empty()) return out;
  Vector5d p = Values(body.front()), v = Vector5d::Zero(), a = Vector5d::Zero();
  if (t >= body.back().t) {
    p = Values(body.back());
  } else if (t > body.front().t) {
    const auto next = std::upper_bound(body.begin(), body.end(), t, [](double value, const BodyState& b) { return value < b.t; });
    const auto k1 = static_cast<std::size_t>(next - body.begin());
    const std::size_t k0 = k1 - 1;
    const double h = body[k1].t - body[k0].t;
    if (h > 0.0) {
      const double s = (t - body[k0].t) / h;
      const Vector5d p0 = Values(body[k0]), p1 = Values(body[k1]);
      const Vector5d m0 = h * Tangent(body, k0), m1 = h * Tangent(body, k1);
      // Cubic Hermite basis and its first two derivatives in s.
      const double s2 = s * s, s3 = s2 * s;
      p = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
      v = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1 + (3 * s2 - 2 * s) * m1) / h;
      a = ((12 * s - 6) * p0 + (6 * s - 4) * m0 + (-12 * s + 6) * p1 + (6 * s - 2) * m1) / (h * h);
    } else {
      p = Values(body[k1]);
    }
  }
  out.pose.position_W = p.head<3>();
  out.pose.pitch = p(3);
  out.pose.yaw = p(4);
  out.velocity_W = v.head<3>();
  out.acceleration_W = a.head<3>();
  out.pitch_rate = v(3);
  out.yaw_rate = v(4);
  return out;
}

}  // namespace stairplan
