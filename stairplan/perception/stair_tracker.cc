#include "stairplan/perception/stair_tracker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "stairplan/geometry/field_error.h"
#include "stairplan/perception/height_map.h"
#include "stairplan/geometry/stair_uncertainty.h"

namespace stairplan {
namespace {

constexpr double kDeg = M_PI / 180.0;

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

struct FittedLine {
  double offset = 0.0;  // value at index 0
  double slope = 0.0;
};

// Weighted least-squares line value = offset + slope * index.
FittedLine FitLine(const std::vector<int>& index, const std::vector<double>& value, const std::vector<double>& weight = {}) {
  const auto w = [&](std::size_t i) { return weight.empty() ? 1.0 : weight[i]; };
  double sw = 0.0, mi = 0.0, mv = 0.0;
  for (std::size_t i = 0; i < index.size(); ++i) {
    sw += w(i);
    mi += w(i) * index[i];
    mv += w(i) * value[i];
  }
  mi /= sw;
  mv /= sw;
  double cov = 0.0, var = 0.0;
  for (std::size_t i = 0; i < index.size(); ++i) {
    cov += w(i) * (index[i] - mi) * (value[i] - mv);
    var += w(i) * (index[i] - mi) * (index[i] - mi);
  }
  FittedLine line;
  line.slope = var > 0.0 ? cov / var : 0.0;
  line.offset = mv - line.slope * mi;
  return line;
}

// Height scatter of the cells about their profile bin's mean, leave-one-out so that sparsely
// filled bins are not rewarded (a lone cell would explain itself perfectly). Along the stairs'
// true heading every bin holds one tread, so the scatter is smallest there.
double ProfileScatter(const std::vector<Eigen::Vector3d>& cells, double theta, double bin, double radius, double variance,
                      std::vector<double>& s, std::vector<double>& s2, std::vector<int>& n) {
  const double c = std::cos(theta), si = std::sin(theta);
  std::fill(s.begin(), s.end(), 0.0);
  std::fill(s2.begin(), s2.end(), 0.0);
  std::fill(n.begin(), n.end(), 0);
  for (const auto& p : cells) {
    const auto b = static_cast<std::size_t>((p.x() * c + p.y() * si + radius) / bin);
    s[b] += p.z();
    s2[b] += p.z() * p.z();
    ++n[b];
  }
  double scatter = 0.0;
  for (std::size_t b = 0; b < s.size(); ++b) {
    if (n[b] == 1) scatter += variance;
    if (n[b] > 1) scatter += (s2[b] - s[b] * s[b] / n[b]) * n[b] / (n[b] - 1.0);
  }
  return scatter;
}

// A level's height from the raw points of its profile bins. A tread seen from above gives many
// bins: their points' median is unbiased. A tread seen only as the top of its riser or nosing
// (above the sensor) gives a bin or two whose highest points are the edge itself.
double LevelHeight(const PointCloud& cloud, const std::vector<double>& u, double u_min, double bin,
                   const std::vector<std::size_t>& cluster, const std::vector<double>& raw_envelope, double level,
                   const StairTrackerSettings& settings, bool* seen) {
  // A tread seen from above: its own bins (not those lifted to it past a nosing) and their points
  // near the level give an unbiased median.
  constexpr double kTreadBand = 0.015;
  std::vector<char> member(raw_envelope.size(), 0), own(raw_envelope.size(), 0);
  int tread_bins = 0;
  for (std::size_t b : cluster) {
    member[b] = 1;
    if (std::abs(raw_envelope[b] - level) < kTreadBand) {
      own[b] = 1;
      ++tread_bins;
    }
  }
  const bool tread_seen = tread_bins * bin >= 0.5 * settings.min_run;
  if (tread_seen) member.swap(own);  // riser faces in the lifted bins would pull the median down
  *seen = tread_seen;
  std::vector<double> z;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto b = static_cast<std::size_t>((u[i] - u_min) / bin);
    if (!member[b]) continue;
    const double dz = cloud.points[i].z() - level;
    if (tread_seen ? std::abs(dz) < kTreadBand : std::abs(dz) < settings.plateau_spread) z.push_back(cloud.points[i].z());
  }
  if (z.empty()) return level;
  // Seen only as the top of its riser or nosing (above the sensor), the highest points are the edge.
  return tread_seen ? Percentile(z, 0.5) : Percentile(z, 0.98);
}

StairFit Reject(const std::string& reason) {
  StairFit fit;
  fit.reason = reason;
  return fit;
}

// Fits the levels and edges along the heading theta (the direction the stairs ascend).
StairFit FitAlong(const PointCloud& cloud, double best_theta, const StairTrackerSettings& settings) {
  const Eigen::Vector2d dir(std::cos(best_theta), std::sin(best_theta));
  const Eigen::Vector2d left(-dir.y(), dir.x());

  // 2. The profile along the direction: per bin, the top of the points, so treads and the tops of
  // risers and nosings show and faces below them do not.
  std::vector<double> u(cloud.size()), v(cloud.size());
  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    u[i] = cloud.points[i].head<2>().dot(dir);
    v[i] = cloud.points[i].head<2>().dot(left);
    u_min = std::min(u_min, u[i]);
    u_max = std::max(u_max, u[i]);
  }
  const auto nbins = static_cast<std::size_t>((u_max - u_min) / settings.bin) + 1;
  // Per bin, the top is taken in slices across the width and the median slice wins, so an object
  // narrower than half the width (a box on a tread) does not lift the profile.
  constexpr double kSlice = 0.08;
  double v_min = std::numeric_limits<double>::infinity(), v_max = -v_min;
  for (double value : v) {
    v_min = std::min(v_min, value);
    v_max = std::max(v_max, value);
  }
  const auto slices = static_cast<std::size_t>((v_max - v_min) / kSlice) + 1;
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<double> slice_top(nbins * slices, lowest);
  std::vector<int> bin_count(nbins, 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto b = static_cast<std::size_t>((u[i] - u_min) / settings.bin);
    const auto sl = static_cast<std::size_t>((v[i] - v_min) / kSlice);
    double& t = slice_top[b * slices + sl];
    t = std::max(t, cloud.points[i].z());
    ++bin_count[b];
  }
  std::vector<double> envelope(nbins, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::size_t> occupied;
  std::vector<double> tops;
  for (std::size_t b = 0; b < nbins; ++b) {
    if (bin_count[b] < 3) continue;  // a bin with a point or two is noise leaking off a riser face
    tops.clear();
    for (std::size_t sl = 0; sl < slices; ++sl) {
      if (slice_top[b * slices + sl] > lowest) tops.push_back(slice_top[b * slices + sl]);
    }
    envelope[b] = Percentile(tops, 0.5);
    occupied.push_back(b);
  }

  // Looking up a flight, the bins just past a nosing see the riser face and the lip's underside,
  // below the nosing's top. Physically the surface just past an edge is the higher tread, so each
  // bin takes the highest top within a nosing's depth before it (the lower side comes first).
  std::vector<double> raw_envelope;
  {
    const int reach = static_cast<int>(std::ceil(settings.nosing_reach / settings.bin));
    std::vector<double> lifted = envelope;
    for (std::size_t b : occupied) {
      for (int k = 1; k <= reach && static_cast<int>(b) - k >= 0; ++k) {
        const double e = envelope[b - static_cast<std::size_t>(k)];
        if (!std::isnan(e)) lifted[b] = std::max(lifted[b], e);
      }
    }
    raw_envelope.swap(envelope);
    envelope.swap(lifted);
  }

  // 3. Plateaus: cluster the profile heights; a cluster that spreads is not a plateau.
  std::vector<std::size_t> order = occupied;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return envelope[a] < envelope[b]; });
  const double split = 0.5 * settings.min_rise;
  std::vector<std::vector<std::size_t>> clusters;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || envelope[order[i]] - envelope[order[i - 1]] > split) clusters.emplace_back();
    clusters.back().push_back(order[i]);
  }
  std::vector<double> level_height;
  std::vector<bool> level_seen;
  std::vector<int> label(nbins, -1);
  int plateau_bins = 0;
  for (const auto& cluster : clusters) {
    std::vector<double> values;
    for (std::size_t b : cluster) values.push_back(envelope[b]);
    // A lone bin is a face's noise, not a level; a wide spread is a slope, not a plateau.
    if (cluster.size() < 2 || Percentile(values, 0.9) - Percentile(values, 0.1) > settings.plateau_spread) continue;
    for (std::size_t b : cluster) label[b] = static_cast<int>(level_height.size());
    bool seen = false;
    level_height.push_back(LevelHeight(cloud, u, u_min, settings.bin, cluster, raw_envelope, Percentile(values, 0.5), settings, &seen));
    level_seen.push_back(seen);
    plateau_bins += static_cast<int>(cluster.size());
  }
  if (plateau_bins < settings.min_plateau_fraction * static_cast<double>(occupied.size())) {
    return Reject("no plateaus: heights vary continuously along the slope (a ramp?)");
  }
  if (static_cast<int>(level_height.size()) < settings.min_risers + 1) {
    return Reject("fewer than " + std::to_string(settings.min_risers) + " risers (found " +
                  std::to_string(std::max<int>(0, static_cast<int>(level_height.size()) - 1)) + ")");
  }

  // 4. Regular rise: level j sits at index round((L_j - L_0) / rise).
  std::vector<double> gaps;
  for (std::size_t j = 1; j < level_height.size(); ++j) gaps.push_back(level_height[j] - level_height[j - 1]);
  const double rise0 = Percentile(gaps, 0.5);
  if (!(rise0 > 0.0)) return Reject("levels are not a regular rise");
  // The offset most levels agree with, then each level's index; a level off the regular rise (the
  // top of an object on a tread) or sharing an index with a better one is dropped, if few are.
  double offset = level_height.front();
  std::vector<int> index(level_height.size());
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> offsets;
    for (std::size_t j = 0; j < level_height.size(); ++j) {
      index[j] = static_cast<int>(std::lround((level_height[j] - offset) / rise0));
      offsets.push_back(level_height[j] - index[j] * rise0);
    }
    offset = Percentile(offsets, 0.5);
  }
  std::vector<char> keep(level_height.size(), 1);
  for (std::size_t j = 0; j < level_height.size(); ++j) {
    const double r = std::abs(level_height[j] - (offset + index[j] * rise0));
    if (r > settings.max_level_residual) keep[j] = 0;
    for (std::size_t i = 0; i < j; ++i) {
      if (!keep[i] || index[i] != index[j]) continue;
      const double ri = std::abs(level_height[i] - (offset + index[i] * rise0));
      keep[ri <= r ? j : i] = 0;
    }
  }
  const auto dropped = std::count(keep.begin(), keep.end(), 0);
  if (dropped > std::max<long>(1, static_cast<long>(level_height.size()) / 4)) return Reject("levels are not a regular rise");
  std::vector<int> relabel(level_height.size(), -1);
  std::vector<double> kept_height;
  std::vector<bool> kept_seen;
  std::vector<int> level_index;
  for (std::size_t j = 0; j < level_height.size(); ++j) {
    if (!keep[j]) continue;
    relabel[j] = static_cast<int>(kept_height.size());
    kept_height.push_back(level_height[j]);
    kept_seen.push_back(level_seen[j]);
    level_index.push_back(index[j]);
  }
  for (int& l : label) l = l < 0 ? -1 : relabel[static_cast<std::size_t>(l)];
  level_height.swap(kept_height);
  level_seen.swap(kept_seen);
  if (static_cast<int>(level_height.size()) < settings.min_risers + 1) return Reject("levels are not a regular rise");
  for (int& i : level_index) i -= index[static_cast<std::size_t>(std::find(keep.begin(), keep.end(), 1) - keep.begin())];
  for (std::size_t j = 1; j < level_index.size(); ++j) {
    if (level_index[j] <= level_index[j - 1]) return Reject("levels are not a regular rise");
  }
  // Treads seen from above give exact levels; a level seen only as the top of a face is as low as
  // the sensor's sampling of that face (and far up the flight, where its leverage on the rise is
  // largest), so it counts for next to nothing when two or more treads were seen.
  const auto seen_count = std::count(level_seen.begin(), level_seen.end(), true);
  std::vector<double> level_weight;
  for (bool seen : level_seen) level_weight.push_back(seen || seen_count < 2 ? 1.0 : 1e-3);
  const FittedLine levels = FitLine(level_index, level_height, level_weight);
  StairFit fit;
  for (std::size_t j = 0; j < level_height.size(); ++j) {
    fit.level_residuals.push_back(level_height[j] - (levels.offset + levels.slope * level_index[j]));
    if (std::abs(fit.level_residuals.back()) > settings.max_level_residual) return Reject("levels are not a regular rise");
  }
  if (levels.slope < settings.min_rise || levels.slope > settings.max_rise) {
    return Reject("rise " + std::to_string(levels.slope) + " m is outside the accepted range");
  }

  // 5. Edges: between consecutive levels, the split of the profile that best puts the lower level
  // before the upper one; the edge is where the upper level starts (the nosing is always seen).
  std::vector<int> edge_index;
  std::vector<double> edge_u, edge_weight;
  for (std::size_t j = 0; j + 1 < level_height.size(); ++j) {
    std::vector<std::size_t> pair_bins;
    int lower_total = 0;
    for (std::size_t b : occupied) {
      if (label[b] == static_cast<int>(j) || label[b] == static_cast<int>(j + 1)) pair_bins.push_back(b);
      if (label[b] == static_cast<int>(j)) ++lower_total;
    }
    const int upper_total = static_cast<int>(pair_bins.size()) - lower_total;
    int best_errors = std::numeric_limits<int>::max();
    std::size_t best_p = 0;
    int upper_before = 0, lower_before = 0;
    for (std::size_t p = 0; p <= pair_bins.size(); ++p) {
      const int errors = upper_before + (lower_total - lower_before);
      if (errors <= best_errors && p < pair_bins.size() && label[pair_bins[p]] == static_cast<int>(j + 1)) {
        best_errors = errors;
        best_p = p;
      }
      if (p < pair_bins.size()) (label[pair_bins[p]] == static_cast<int>(j) ? lower_before : upper_before)++;
    }
    if (best_errors > 0.25 * std::min(lower_total, upper_total) + 1) {
      return Reject("the levels do not climb in one direction (a box or a pit?)");
    }
    const double u_b = u_min + static_cast<double>(pair_bins[best_p]) * settings.bin;
    // The upper level's front: its points near the split (bins too sparse to count may hold the
    // nosing itself, so look back a few centimetres; lower-level points are below z_top).
    constexpr double kEdgeLookBack = 0.05;
    std::vector<double> near;
    const double z_top = level_height[j + 1] - 0.5 * (level_height[j + 1] - level_height[j]);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (u[i] >= u_b - kEdgeLookBack && u[i] <= u_b + 3 * settings.bin && cloud.points[i].z() > z_top) near.push_back(u[i]);
    }
    edge_index.push_back(level_index[j + 1]);
    edge_u.push_back(near.empty() ? u_b : Percentile(near, 0.3));
    edge_weight.push_back(static_cast<double>(std::clamp<std::size_t>(near.size(), 1, 200)));
  }
  // Far edges are sampled sparsely and land a bin or two off: they count for less.
  const FittedLine edges = FitLine(edge_index, edge_u, edge_weight);  // edge k at offset + k * run
  for (std::size_t k = 0; k < edge_u.size(); ++k) {
    fit.edge_residuals.push_back(edge_u[k] - (edges.offset + edges.slope * edge_index[k]));
  }
  for (double r : fit.edge_residuals) {
    if (std::abs(r) > settings.max_edge_residual) return Reject("edges are not at a regular run");
  }
  if (edge_u.size() >= 2 && (edges.slope < settings.min_run || edges.slope > settings.max_run)) {
    return Reject("run " + std::to_string(edges.slope) + " m is outside the accepted range");
  }

  // 6. The model, its width from the spread across, and the residuals.
  StairModel& m = fit.model;
  m.steps = level_index.back();
  m.rise = levels.slope;
  m.run = edges.slope;
  m.direction = dir;
  const double v_lo = Percentile(v, 0.005), v_hi = Percentile(v, 0.995);
  m.width = v_hi - v_lo;
  const double first_edge = edges.offset + edges.slope * 1.0;
  m.center = first_edge * dir + 0.5 * (v_lo + v_hi) * left;
  for (int k = 0; k <= m.steps; ++k) m.levels.push_back(levels.offset + levels.slope * k);
  for (int k = 1; k <= m.steps; ++k) m.edge_offsets.push_back((k - 1) * m.run);
  const auto sq = [](double a) { return a * a; };
  double level_ss = 0.0, edge_ss = 0.0, point_ss = 0.0;
  for (double r : fit.level_residuals) level_ss += sq(r);
  for (double r : fit.edge_residuals) edge_ss += sq(r);
  fit.level_rms = std::sqrt(level_ss / static_cast<double>(fit.level_residuals.size()));
  fit.edge_rms = std::sqrt(edge_ss / static_cast<double>(fit.edge_residuals.size()));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double along = (u[i] - first_edge) / m.run + 1.0;  // edge k sits at along == k
    const int k = std::clamp(static_cast<int>(std::floor(along)), 0, m.steps);
    const double to_edge = std::abs(along - std::round(along)) * m.run;
    const double dz = cloud.points[i].z() - m.levels[static_cast<std::size_t>(k)];
    if (to_edge < 0.03 || std::abs(dz) > 0.5 * m.rise) continue;
    point_ss += sq(dz);
    ++fit.tread_points;
  }
  fit.point_rms = fit.tread_points > 0 ? std::sqrt(point_ss / fit.tread_points) : 0.0;
  // How far the nosings may be off, from the scatter of every level and edge about a regular
  // staircase. The levels seen only as face tops count in full here: the fit barely listens to
  // them, and their shortfall (up to a centimetre on the default scan) is what it does not know
  // about the upper treads, where a rise fitted on the lowest few is extrapolated. A level's own
  // error is taken as its tread points' scatter about the model (point_rms): the median of points
  // seen at grazing incidence reads low by a share of that scatter that grows up the flight, a bias
  // the residuals of a regular rise cannot show (on the default scan the rise comes out 0.4-1.1 mm
  // short per step, 3-8 mm at the top, with residuals under 1 mm on the treads seen).
  {
    IndexedSamples level_samples, edge_samples;
    for (std::size_t j = 0; j < level_height.size(); ++j) {
      level_samples.index.push_back(level_index[j]);
      level_samples.value.push_back(level_height[j]);
    }
    level_samples.sample_sigma = fit.point_rms;
    for (std::size_t k = 0; k < edge_u.size(); ++k) {
      edge_samples.index.push_back(edge_index[k]);
      edge_samples.value.push_back(edge_u[k]);
    }
    // One edge (min_risers 1) fixes no run: nothing to bound it by, the model says 0.
    if (edge_samples.index.size() >= 2) m.uncertainty = NosingUncertainty(level_samples, edge_samples, m.steps);
  }
  fit.found = true;
  return fit;
}

// The heading that makes the edges straight across the width: for every edge, the front of the
// points at its upper level is sampled in slices across the width, and one slope shared by all
// edges is fitted; the edges' normal is the refined heading.
double RefineHeading(const PointCloud& cloud, const StairModel& m, double theta) {
  constexpr double kSlice = 0.04, kWindow = 0.05;
  const Eigen::Vector2d dir(std::cos(theta), std::sin(theta)), left(-dir.y(), dir.x());
  const double first = m.center.dot(dir);
  const int slices = static_cast<int>(std::ceil(m.width / kSlice)) + 4;
  const double v0 = m.center.dot(left) - 0.5 * slices * kSlice;
  std::vector<std::vector<std::vector<double>>> fronts(m.edge_offsets.size(), std::vector<std::vector<double>>(static_cast<std::size_t>(slices)));
  for (const auto& p : cloud.points) {
    const double u = p.head<2>().dot(dir), v = p.head<2>().dot(left);
    const double along = (u - first) / m.run;
    const long k = std::lround(along);
    if (k < 0 || k >= static_cast<long>(m.edge_offsets.size())) continue;
    const double edge_u = first + m.edge_offsets[static_cast<std::size_t>(k)];
    if (std::abs(u - edge_u) > kWindow) continue;
    const auto ku = static_cast<std::size_t>(k);
    if (p.z() < 0.5 * (m.levels[ku] + m.levels[ku + 1])) continue;
    const int slice = static_cast<int>((v - v0) / kSlice);
    if (slice < 0 || slice >= slices) continue;
    fronts[ku][static_cast<std::size_t>(slice)].push_back(u);
  }
  double num = 0.0, den = 0.0;
  for (const auto& edge : fronts) {
    std::vector<double> vs, us;
    for (int s = 0; s < slices; ++s) {
      const auto& values = edge[static_cast<std::size_t>(s)];
      if (values.size() < 3) continue;
      vs.push_back(v0 + (s + 0.5) * kSlice);
      us.push_back(Percentile(values, 0.1));
    }
    if (vs.size() < 4) continue;
    const double mv = std::accumulate(vs.begin(), vs.end(), 0.0) / static_cast<double>(vs.size());
    const double mu = std::accumulate(us.begin(), us.end(), 0.0) / static_cast<double>(us.size());
    for (std::size_t i = 0; i < vs.size(); ++i) {
      num += (vs[i] - mv) * (us[i] - mu);
      den += (vs[i] - mv) * (vs[i] - mv);
    }
  }
  if (den <= 0.0) return theta;
  // Edges run along u = a + b v; their normal in (u, v) is (1, -b).
  return theta - std::atan(num / den);
}

}  // namespace

void StairTrackerSettings::Validate() const {
  if (!(min_rise > 0.0 && max_rise > min_rise && max_rise < 2.0)) throw FieldError("min_rise/max_rise", "need 0 < min_rise < max_rise < 2 m");
  if (!(min_run > 0.0 && max_run > min_run && max_run < 5.0)) throw FieldError("min_run/max_run", "need 0 < min_run < max_run < 5 m");
  if (min_risers < 1) throw FieldError("min_risers", "must be >= 1");
  if (!(cell >= 0.005 && cell <= 0.2)) throw FieldError("cell", "must be in [0.005, 0.2] m");
  if (!(bin >= 0.002 && bin <= 0.1)) throw FieldError("bin", "must be in [0.002, 0.1] m");
  if (!(plateau_spread > 0.0 && plateau_spread < min_rise)) throw FieldError("plateau_spread", "must be in (0, min_rise)");
  if (!(min_plateau_fraction >= 0.0 && min_plateau_fraction <= 1.0)) throw FieldError("min_plateau_fraction", "must be in [0, 1]");
  if (!(max_level_residual > 0.0)) throw FieldError("max_level_residual", "must be positive");
  if (!(max_edge_residual > 0.0)) throw FieldError("max_edge_residual", "must be positive");
}

StairFit FitStairs(const PointCloud& cloud, const StairTrackerSettings& settings) {
  settings.Validate();
  if (cloud.empty()) throw std::invalid_argument("FitStairs: the point cloud is empty");

  // 1. Heading: the direction along which the surface's profile is sharpest, from a coarse map.
  HeightMapSettings map_settings;
  map_settings.resolution = settings.cell;
  const HeightMap map = HeightMap::FromCloud(cloud, map_settings);
  std::vector<Eigen::Vector3d> cells;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int iy = 0; iy < map.ny(); ++iy) {
    for (int ix = 0; ix < map.nx(); ++ix) {
      if (map.state(ix, iy) != CellState::kMeasured) continue;
      const Eigen::Vector2d c = map.CellCenter(ix, iy);
      cells.emplace_back(c.x(), c.y(), map.height(ix, iy));
      mean += c;
    }
  }
  mean /= static_cast<double>(cells.size());
  double radius = 0.0, z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (auto& p : cells) {
    p.head<2>() -= mean;
    radius = std::max(radius, p.head<2>().norm());
    z_lo = std::min(z_lo, p.z());
    z_hi = std::max(z_hi, p.z());
  }
  if (z_hi - z_lo < settings.min_rise) return Reject("flat: the heights span less than one minimum rise");
  radius += settings.bin;
  double variance = 0.0, mean_z = 0.0;
  for (const auto& p : cells) mean_z += p.z();
  mean_z /= static_cast<double>(cells.size());
  for (const auto& p : cells) variance += (p.z() - mean_z) * (p.z() - mean_z);
  variance /= static_cast<double>(cells.size());
  // Coarse bins (well under the shortest run) for the whole circle, then fine ones near the best.
  const double coarse_bin = std::max(settings.bin, settings.min_run / 4.0);
  std::vector<double> s, s2;
  std::vector<int> n;
  const auto search = [&](double bin, double from, double step, int count) {
    const auto bins = static_cast<std::size_t>(2.0 * radius / bin) + 2;
    s.resize(bins);
    s2.resize(bins);
    n.resize(bins);
    double best = std::numeric_limits<double>::infinity(), best_theta = from;
    for (int i = 0; i < count; ++i) {
      const double theta = from + i * step;
      const double value = ProfileScatter(cells, theta, bin, radius, variance, s, s2, n);
      if (value < best) {
        best = value;
        best_theta = theta;
      }
    }
    return best_theta;
  };
  const double coarse = search(coarse_bin, 0.0, kDeg, 180);
  const double medium = search(settings.bin, coarse - 2.0 * kDeg, 0.25 * kDeg, 17);
  double best_theta = search(settings.bin, medium - 0.3 * kDeg, 0.02 * kDeg, 31);
  // Ascending: height grows along the direction.
  {
    double cov = 0.0, mz = 0.0;
    for (const auto& p : cells) mz += p.z();
    mz /= static_cast<double>(cells.size());
    for (const auto& p : cells) cov += (p.x() * std::cos(best_theta) + p.y() * std::sin(best_theta)) * (p.z() - mz);
    if (cov < 0.0) best_theta += M_PI;
  }
  // 2. Fit along the heading, then straighten the heading on the edges found and fit again.
  StairFit fit = FitAlong(cloud, best_theta, settings);
  for (int pass = 0; pass < 2 && fit.found; ++pass) {
    const double refined = RefineHeading(cloud, fit.model, best_theta);
    if (std::abs(refined - best_theta) < 0.01 * kDeg) break;
    StairFit again = FitAlong(cloud, refined, settings);
    if (!again.found) break;
    fit = std::move(again);
    best_theta = refined;
  }
  return fit;
}

}  // namespace stairplan
