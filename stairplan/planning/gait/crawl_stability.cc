#include "stairplan/planning/gait/crawl_stability.h"

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

// The paper's legs in the order RH, LH, RF, LF, at the contact offsets of `arrangement`.
std::array<CrawlLeg, 4> CrawlLegs(const GaitDesignInput& input, const GaitDesign& g, CrawlCase arrangement) {
  const bool switched = arrangement == CrawlCase::kFrontSwitched;
  return {{
      {"RH", 0.0, -1.0, g.a_min},
      {"LH", 0.0, 1.0, g.a_max},
      {"RF", input.body_length, -1.0, switched ? g.a_max : g.a_min},
      {"LF", input.body_length, 1.0, switched ? g.a_min : g.a_max},
  }};
}

// A leg with contact offset a leaves step j when its hip reaches (j + 1/2) CL + a cos(phi) along
// the slope: there its hip is equidistant from both contacts (the paper's Figure 2(a)).
double LiftPhase(const GaitDesign& g, const CrawlLeg& leg) { return 0.5 * g.cl + leg.a * std::cos(g.phi); }

CrawlInstant InstantOf(const GaitDesignInput& input, const GaitDesign& g, const std::array<CrawlLeg, 4>& legs, double s) {
  CrawlInstant instant;
  std::array<Eigen::Vector2d, 4> feet;
  int stance = 0;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const double z = s + legs[i].hip_offset - LiftPhase(g, legs[i]);
    const double j = std::floor(z / g.cl);
    if (z - j * g.cl < g.d_i) {
      ++instant.legs_in_air;
      instant.swing_leg = static_cast<int>(i);
      continue;
    }
    feet[static_cast<std::size_t>(stance++)] = {(j + 1.0) * input.run + legs[i].a, legs[i].side * 0.5 * input.body_width};
  }
  const Eigen::Vector2d com((s + 0.5 * input.body_length) * std::cos(g.phi) - g.d * std::sin(g.phi), 0.0);
  instant.margin = instant.legs_in_air > 1 ? -std::numeric_limits<double>::infinity() : HullMargin(feet, stance, com);
  return instant;
}

}  // namespace

CrawlInstant CrawlStabilityAt(const GaitDesignInput& input, const GaitDesign& design, CrawlCase arrangement,
                              double hind_hip) {
  return InstantOf(input, design, CrawlLegs(input, design, arrangement), hind_hip);
}

CrawlStability EvaluateCrawlStability(const GaitDesignInput& input, const GaitDesign& g, CrawlCase arrangement,
                                      int samples) {
  if (!(g.d_s > 0.0)) throw std::invalid_argument("EvaluateCrawlStability: design: needs D_s > 0 (condition (10))");
  if (samples < 4) throw std::invalid_argument("EvaluateCrawlStability: samples must be >= 4");
  const std::array<CrawlLeg, 4> legs = CrawlLegs(input, g, arrangement);

  CrawlStability result;
  result.arrangement = arrangement;
  // The order of swing starts within one cycle, measured on the hind hip, from the hind right.
  std::array<std::pair<double, const char*>, 4> starts;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const double start = LiftPhase(g, legs[i]) - legs[i].hip_offset - LiftPhase(g, legs[0]);
    starts[i] = {Remainder(start, g.cl), legs[i].name};
  }
  std::stable_sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < 4; ++i) result.swing_sequence[i] = starts[i].second;

  int outside = 0, airborne = 0;
  std::array<int, 4> by_leg{};
  for (int k = 0; k < samples; ++k) {
    const double s = g.cl * (static_cast<double>(k) + 0.5) / samples;  // hind hip along the slope
    const CrawlInstant instant = InstantOf(input, g, legs, s);
    if (instant.legs_in_air > 0) ++airborne;
    result.min_margin = k == 0 ? instant.margin : std::min(result.min_margin, instant.margin);
    if (instant.margin < -1e-12) {
      ++outside;
      if (instant.swing_leg >= 0) ++by_leg[static_cast<std::size_t>(instant.swing_leg)];
    }
  }
  result.fraction_outside = static_cast<double>(outside) / samples;
  result.fraction_of_swing_time = airborne > 0 ? static_cast<double>(outside) / airborne : 0.0;
  for (std::size_t i = 0; i < 4; ++i) result.fraction_outside_by_leg[i] = static_cast<double>(by_leg[i]) / samples;
  return result;
}

double HindSwingShare(const GaitDesign& design) { return 2.0 * design.d_i / design.cl; }

}  // namespace stairplan
