#include "planning/gait/crawl_stability.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Core>

namespace stairplan {
namespace {

struct CrawlLeg {
  const char* name;
  double hip_offset;  // along the slope, from the hind hip [m]
  double side;        // -1 right, +1 left
  double a;           // contact offset [m]
};

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// The distance from c to the nearest edge line of the convex hull of `points` (n <= 4), positive
// inside, negative outside; -infinity when the hull is degenerate.
double HullMargin(std::array<Eigen::Vector2d, 4> points, int n, const Eigen::Vector2d& c) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  if (n < 3 || n > 4) return kNone;
  // Insertion sort by (x, y): n is at most four.
  for (int i = 1; i < n; ++i) {
    for (int j = i; j > 0; --j) {
      const Eigen::Vector2d& p = points[static_cast<std::size_t>(j - 1)];
      const Eigen::Vector2d& q = points[static_cast<std::size_t>(j)];
      if (q.x() < p.x() || (q.x() == p.x() && q.y() < p.y())) {
        std::swap(points[static_cast<std::size_t>(j - 1)], points[static_cast<std::size_t>(j)]);
      } else {
        break;
      }
    }
  }
  // Andrew's monotone chain on at most four points.
  std::array<Eigen::Vector2d, 10> hull;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && Cross(hull[static_cast<std::size_t>(k - 2)], hull[static_cast<std::size_t>(k - 1)], points[static_cast<std::size_t>(i)]) <= 0.0) --k;
    hull[static_cast<std::size_t>(k++)] = points[static_cast<std::size_t>(i)];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && Cross(hull[static_cast<std::size_t>(k - 2)], hull[static_cast<std::size_t>(k - 1)], points[static_cast<std::size_t>(i)]) <= 0.0) --k;
    hull[static_cast<std::size_t>(k++)] = points[static_cast<std::size_t>(i)];
  }
  const int m = k - 1;
  if (m < 3) return kNone;
  double margin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d& a = hull[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& b = hull[static_cast<std::size_t>((i + 1) % m)];
    margin = std::min(margin, Cross(a, b, c) / (b - a).norm());
  }
  return margin;
}

}  // namespace

CrawlStability EvaluateCrawlStability(const GaitDesignInput& input, const GaitDesign& g, CrawlCase arrangement,
                                      int samples) {
  if (!(g.d_s > 0.0)) throw std::invalid_argument("EvaluateCrawlStability: design: needs D_s > 0 (condition (10))");
  if (samples < 4) throw std::invalid_argument("EvaluateCrawlStability: samples must be >= 4");
  const bool switched = arrangement == CrawlCase::kFrontSwitched;
  const std::array<CrawlLeg, 4> legs = {{
      {"RH", 0.0, -1.0, g.a_min},
      {"LH", 0.0, 1.0, g.a_max},
      {"RF", input.body_length, -1.0, switched ? g.a_max : g.a_min},
      {"LF", input.body_length, 1.0, switched ? g.a_min : g.a_max},
  }};
  const double cos_phi = std::cos(g.phi);
  const double sin_phi = std::sin(g.phi);
  // A leg with contact offset a leaves step j when its hip reaches (j + 1/2) CL + a cos(phi) along
  // the slope: there its hip is equidistant from both contacts (the paper's Figure 2(a)).
  const auto lift_phase = [&](const CrawlLeg& leg) { return 0.5 * g.cl + leg.a * cos_phi; };

  CrawlStability result;
  result.arrangement = arrangement;
  // The order of swing starts within one cycle, measured on the hind hip, from the hind right.
  std::array<std::pair<double, const char*>, 4> starts;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const double start = lift_phase(legs[i]) - legs[i].hip_offset - lift_phase(legs[0]);
    starts[i] = {Remainder(start, g.cl), legs[i].name};
  }
  std::stable_sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < 4; ++i) result.swing_sequence[i] = starts[i].second;

  int outside = 0, airborne = 0;
  std::array<int, 4> by_leg{};
  for (int k = 0; k < samples; ++k) {
    const double s = g.cl * (static_cast<double>(k) + 0.5) / samples;  // hind hip along the slope
    std::array<Eigen::Vector2d, 4> feet;
    int stance = 0, swinging = 0, swing_leg = -1;
    for (std::size_t i = 0; i < legs.size(); ++i) {
      const double z = s + legs[i].hip_offset - lift_phase(legs[i]);
      const double j = std::floor(z / g.cl);
      if (z - j * g.cl < g.d_i) {
        ++swinging;
        swing_leg = static_cast<int>(i);
        continue;
      }
      feet[static_cast<std::size_t>(stance++)] = {(j + 1.0) * input.run + legs[i].a, legs[i].side * 0.5 * input.body_width};
    }
    if (swinging > 0) ++airborne;
    const Eigen::Vector2d com((s + 0.5 * input.body_length) * cos_phi - g.d * sin_phi, 0.0);
    const double margin = swinging > 1 ? -std::numeric_limits<double>::infinity() : HullMargin(feet, stance, com);
    result.min_margin = k == 0 ? margin : std::min(result.min_margin, margin);
    if (margin < -1e-12) {
      ++outside;
      if (swing_leg >= 0) ++by_leg[static_cast<std::size_t>(swing_leg)];
    }
  }
  result.fraction_outside = static_cast<double>(outside) / samples;
  result.fraction_of_swing_time = airborne > 0 ? static_cast<double>(outside) / airborne : 0.0;
  for (std::size_t i = 0; i < 4; ++i) result.fraction_outside_by_leg[i] = static_cast<double>(by_leg[i]) / samples;
  return result;
}

double HindSwingShare(const GaitDesign& design) { return 2.0 * design.d_i / design.cl; }

}  // namespace stairplan
