#include "stairplan/perception/footfall_walk.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {

struct Foothold {
  Eigen::Vector3d point;  // on the path's centre line [m]
  double heading = 0.0;   // of the path there [rad]
};

// The centre-line footholds over one flight, in travel order: up to the first edge at the
// stride, the last one half a run before it (aligned with the treads), one per tread centre,
// then on past the last edge the same way.
std::vector<Foothold> FlightFootholds(const PlacedFlight& f, double stride) {
  const Staircase& s = f.stairs;
  const double first_edge = s.edges().front().x_nose;
  const double last_edge = s.edges().back().x_nose;
  const double run = s.spec().run;
  std::vector<double> xs;
  for (double x = first_edge - 0.5 * run; x >= s.x_min() + 0.1; x -= stride) xs.push_back(x);
  std::reverse(xs.begin(), xs.end());
  for (int k = 1; k < s.steps(); ++k) xs.push_back(0.5 * (s.surface(k).x_begin + s.surface(k).x_end));
  for (double x = last_edge + 0.5 * run; x <= s.x_max() - 0.1; x += stride) xs.push_back(x);
  const Eigen::Vector2d axis(std::cos(f.yaw), std::sin(f.yaw));
  std::vector<Foothold> out;
  for (double x : xs) {
    Foothold h;
    h.point << f.origin_W.head<2>() + x * axis, f.origin_W.z() + s.HeightAt(x, 0.0);
    h.heading = f.yaw;
    out.push_back(h);
  }
  return out;
}

}  // namespace

void FootfallWalkSettings::Validate() const {
  if (!(stride > 0.05 && stride < 2.0)) throw FieldError("stride", "must be in (0.05, 2) m");
  if (!(half_stance >= 0.0 && half_stance < 1.0)) throw FieldError("half_stance", "must be in [0, 1) m");
  if (!(step_period > 0.0 && step_period < 60.0)) throw FieldError("step_period", "must be in (0, 60) s");
  if (!(placement_scatter >= 0.0 && placement_scatter < 0.1)) throw FieldError("placement_scatter", "must be in [0, 0.1) m");
  if (!(sigma >= 0.0 && sigma < 0.5)) throw FieldError("sigma", "must be in [0, 0.5) m");
}

std::vector<Footfall> WalkFootfalls(const std::vector<PlacedFlight>& route, const FootfallWalkSettings& settings) {
  settings.Validate();
  std::vector<Foothold> path;
  for (const PlacedFlight& flight : route) {
    const std::vector<Foothold> holds = FlightFootholds(flight, settings.stride);
    if (!path.empty() && !holds.empty()) {
      // A straight walk from the last foothold to the next flight's first one.
      const Eigen::Vector3d a = path.back().point, b = holds.front().point;
      const double length = (b - a).head<2>().norm();
      const int n = static_cast<int>(std::ceil(length / settings.stride));
      const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
      for (int i = 1; i < n; ++i) path.push_back({a + (b - a) * (static_cast<double>(i) / n), heading});
    }
    path.insert(path.end(), holds.begin(), holds.end());
  }
  std::mt19937 rng(settings.seed);
  std::uniform_real_distribution<double> scatter(-settings.placement_scatter, settings.placement_scatter);
  std::normal_distribution<double> noise(0.0, settings.sigma);
  // A crawl: the front feet take the footholds in turn, the hind feet step into them two periods
  // later; left and right a quarter period apart.
  struct Leg {
    const char* name;
    double side;
    double delay;
  };
  const Leg legs[4] = {{"LF", 1.0, 0.0}, {"RF", -1.0, 0.25}, {"LH", 1.0, 2.5}, {"RH", -1.0, 2.75}};
  std::vector<Footfall> footfalls;
  footfalls.reserve(path.size() * 4);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector2d along(std::cos(path[i].heading), std::sin(path[i].heading));
    const Eigen::Vector2d left(-along.y(), along.x());
    for (const Leg& leg : legs) {
      Footfall f;
      f.leg = leg.name;
      f.t = (static_cast<double>(i) + leg.delay) * settings.step_period;
      // One draw per statement: as function or operator arguments their order is unspecified
      // (gcc drew right to left, clang left to right), which gave each compiler its own walk for
      // a seed. This is the order gcc used, so the walks the tests were tuned on stay the same.
      const double along_scatter = scatter(rng);
      const double across_scatter = scatter(rng);
      const double noise_z = noise(rng);
      const double noise_y = noise(rng);
      const double noise_x = noise(rng);
      f.position = path[i].point;
      f.position.head<2>() += (leg.side * settings.half_stance + across_scatter) * left + along_scatter * along;
      f.position += Eigen::Vector3d(noise_x, noise_y, noise_z);
      footfalls.push_back(f);
    }
  }
  std::stable_sort(footfalls.begin(), footfalls.end(), [](const Footfall& a, const Footfall& b) { return a.t < b.t; });
  return footfalls;
}

}  // namespace stairplan
