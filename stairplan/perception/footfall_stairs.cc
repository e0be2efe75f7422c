#include "stairplan/perception/footfall_stairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

#include "stairplan/geometry/field_error.h"
#include "stairplan/geometry/stair_uncertainty.h"

namespace stairplan {
namespace {

// Footfalls hashed on a horizontal grid whose cell is the largest pair separation, so every
// partner of a footfall is in its own or a neighbouring cell.
class FootfallGrid {
 public:
  FootfallGrid(const std::vector<Footfall>& footfalls, double cell) : cell_(cell) {
    for (std::size_t i = 0; i < footfalls.size(); ++i) cells_[Key(footfalls[i].position)].push_back(static_cast<int>(i));
  }
  template <typename Fn>
  void ForNeighbours(const Eigen::Vector3d& p, Fn fn) const {
    const std::int64_t cx = Cell(p.x()), cy = Cell(p.y());
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(Pack(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int j : it->second) fn(j);
      }
    }
  }

 private:
  // Shifted as unsigned: a left shift of a negative signed value is undefined in C++17 (UBSan).
  static std::int64_t Pack(std::int64_t x, std::int64_t y) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffu));
  }
  // Clamped before the cast: a coordinate far beyond int64's range of cells would be undefined.
  std::int64_t Cell(double v) const { return static_cast<std::int64_t>(std::clamp(std::floor(v / cell_), -1e15, 1e15)); }
  std::int64_t Key(const Eigen::Vector3d& p) const { return Pack(Cell(p.x()), Cell(p.y())); }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

struct Pair {
  int low = 0;   // the lower footfall
  int high = 0;  // the higher one
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, horizontal, low to high
};

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) i = parent_[static_cast<std::size_t>(i)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
    return i;
  }
  void Join(int a, int b) { parent_[static_cast<std::size_t>(Find(a))] = Find(b); }

 private:
  std::vector<int> parent_;
};

// True when a footfall other than a and b lies between them: inside the corridor around the
// segment, away from both ends.
bool Intervened(const std::vector<Footfall>& f, const FootfallGrid& grid, int a, int b, double corridor) {
  const Eigen::Vector2d pa = f[static_cast<std::size_t>(a)].position.head<2>(), pb = f[static_cast<std::size_t>(b)].position.head<2>();
  const Eigen::Vector2d ab = pb - pa;
  const double len2 = ab.squaredNorm();
  bool found = false;
  grid.ForNeighbours(f[static_cast<std::size_t>(a)].position, [&](int c) {
    if (found || c == a || c == b) return;
    const Eigen::Vector2d ac = f[static_cast<std::size_t>(c)].position.head<2>() - pa;
    const double t = ac.dot(ab) / len2;
    if (t <= 0.15 || t >= 0.85) return;
    const double across = std::abs(ab.x() * ac.y() - ab.y() * ac.x()) / std::sqrt(len2);
    found = across < 0.5 * corridor;
  });
  return found;
}

Eigen::Vector2d LeftOf(const Eigen::Vector2d& d) { return Eigen::Vector2d(-d.y(), d.x()); }

// Pairs within this angle of the centroids' direction step straight up the flight [rad].
constexpr double kStraightPair = 20.0 * M_PI / 180.0;

// Least-squares slope and intercept of values against 0, 1, 2, ...
std::pair<double, double> FitIndexLine(const std::vector<double>& v) {
  const double n = static_cast<double>(v.size());
  const double mi = 0.5 * (n - 1.0);
  const double mv = std::accumulate(v.begin(), v.end(), 0.0) / n;
  double cov = 0.0, var = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    cov += (static_cast<double>(i) - mi) * (v[i] - mv);
    var += (static_cast<double>(i) - mi) * (static_cast<double>(i) - mi);
  }
  const double slope = var > 0.0 ? cov / var : 0.0;
  return {mv - slope * mi, slope};
}

// One staircase from its footfalls' clusters, lowest first.
FootfallStaircase BuildStaircase(const std::vector<Footfall>& f, const std::vector<std::vector<int>>& clusters,
                                 const std::vector<Eigen::Vector2d>& pair_directions, const FootfallStairsSettings& settings) {
  FootfallStaircase s;
  for (const auto& cluster : clusters) {
    s.footfalls.insert(s.footfalls.end(), cluster.begin(), cluster.end());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i : cluster) sum += f[static_cast<std::size_t>(i)].position;
    s.centroids.push_back(sum / static_cast<double>(cluster.size()));
    s.tread_heights.push_back(s.centroids.back().z());
    s.cluster_sizes.push_back(static_cast<int>(cluster.size()));
  }
  // The direction: the principal axis of the centroids, pointing from the lowest to the highest.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& c : s.centroids) mean += c.head<2>();
  mean /= static_cast<double>(s.centroids.size());
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const auto& c : s.centroids) {
    const Eigen::Vector2d d = c.head<2>() - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  const double axis = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // the 2x2 scatter's major axis
  Eigen::Vector2d dir(std::cos(axis), std::sin(axis));
  if ((s.centroids.back() - s.centroids.front()).head<2>().dot(dir) < 0.0) dir = -dir;
  // A centroid moves sideways when a tread caught more left than right feet; the pairs that step
  // straight up the flight (one foot from tread to tread) are immune, so their mean refines it.
  Eigen::Vector2d straight = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& d : pair_directions) {
    if (d.dot(dir) > std::cos(kStraightPair)) straight += d;
  }
  if (straight.norm() > 0.0) dir = straight.normalized();
  const Eigen::Vector2d left = LeftOf(dir);
  // Edges through the midpoint of the closest footfalls of adjacent clusters.
  std::vector<double> along;
  for (std::size_t j = 0; j + 1 < clusters.size(); ++j) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector2d mid = Eigen::Vector2d::Zero();
    for (int a : clusters[j]) {
      for (int b : clusters[j + 1]) {
        const Eigen::Vector2d pa = f[static_cast<std::size_t>(a)].position.head<2>(), pb = f[static_cast<std::size_t>(b)].position.head<2>();
        const double d = (pb - pa).squaredNorm();
        if (d < best) {
          best = d;
          mid = 0.5 * (pa + pb);
        }
      }
    }
    FootfallEdge e;
    e.midpoint << mid, s.tread_heights[j + 1];
    e.along = left;
    s.edges.push_back(e);
    along.push_back(mid.dot(dir));
  }
  // The regular model: rise and run by least squares; centred across on the footfalls.
  double lat_lo = std::numeric_limits<double>::infinity(), lat_hi = -lat_lo, lat_sum = 0.0;
  int count = 0;
  s.t_begin = std::numeric_limits<double>::infinity();
  s.t_end = -s.t_begin;
  double t_low = 0.0, t_high = 0.0;
  for (std::size_t j = 0; j < clusters.size(); ++j) {
    for (int i : clusters[j]) {
      const Footfall& ff = f[static_cast<std::size_t>(i)];
      const double lat = ff.position.head<2>().dot(left);
      lat_lo = std::min(lat_lo, lat);
      lat_hi = std::max(lat_hi, lat);
      lat_sum += lat;
      ++count;
      s.t_begin = std::min(s.t_begin, ff.t);
      s.t_end = std::max(s.t_end, ff.t);
      if (j == 0) t_low += ff.t / static_cast<double>(clusters[j].size());
      if (j + 1 == clusters.size()) t_high += ff.t / static_cast<double>(clusters[j].size());
    }
  }
  s.traversal = t_low <= t_high ? TravelDirection::kUp : TravelDirection::kDown;
  const auto [z0, rise] = FitIndexLine(s.tread_heights);
  const auto [s0, run] = FitIndexLine(along);
  StairModel& m = s.model;
  m.direction = dir;
  m.steps = static_cast<int>(clusters.size()) - 1;
  m.rise = rise;
  m.run = run;
  m.width = lat_hi - lat_lo + 2.0 * settings.width_margin;
  m.center = s0 * dir + (lat_sum / count) * left;
  for (int k = 0; k <= m.steps; ++k) m.levels.push_back(z0 + rise * k);
  for (int k = 0; k < m.steps; ++k) m.edge_offsets.push_back(run * k);
  // How far the nosings may be off. A tread's height is its footfalls' mean: their scatter about
  // it (pooled over the treads) over the root of their number is its own error. An edge is the
  // midpoint of two footfalls: the same scatter, taken as the sensor's in every direction, over
  // root two.
  IndexedSamples level_samples, edge_samples;
  double scatter = 0.0, tread_footfalls = 0.0;
  int dof = 0;
  for (std::size_t j = 0; j < clusters.size(); ++j) {
    level_samples.index.push_back(static_cast<double>(j));
    level_samples.value.push_back(s.tread_heights[j]);
    for (int i : clusters[j]) scatter += std::pow(f[static_cast<std::size_t>(i)].position.z() - s.tread_heights[j], 2);
    dof += static_cast<int>(clusters[j].size()) - 1;
    tread_footfalls += static_cast<double>(clusters[j].size());
  }
  const double footfall_sigma = dof > 0 ? std::sqrt(scatter / dof) : 0.0;
  level_samples.sample_sigma = footfall_sigma / std::sqrt(tread_footfalls / static_cast<double>(clusters.size()));
  for (std::size_t j = 0; j < along.size(); ++j) {
    edge_samples.index.push_back(static_cast<double>(j + 1));
    edge_samples.value.push_back(along[j]);
  }
  edge_samples.sample_sigma = footfall_sigma / std::sqrt(2.0);
  if (edge_samples.index.size() >= 2) m.uncertainty = NosingUncertainty(level_samples, edge_samples, m.steps);
  return s;
}

}  // namespace

void FootfallStairsSettings::Validate() const {
  if (!(min_rise > 0.0 && max_rise > min_rise)) throw FieldError("min_rise/max_rise", "need 0 < min_rise < max_rise");
  if (!(min_depth >= 0.0 && max_depth > min_depth && max_depth < 10.0)) throw FieldError("min_depth/max_depth", "need 0 <= min_depth < max_depth < 10 m");
  if (!(corridor >= 0.0)) throw FieldError("corridor", "must be >= 0");
  if (!(height_tolerance > 0.0 && height_tolerance < min_rise)) throw FieldError("height_tolerance", "must be in (0, min_rise)");
  if (!(direction_tolerance > 0.0 && direction_tolerance <= M_PI)) throw FieldError("direction_tolerance", "must be in (0, pi]");
  if (min_risers < 1) throw FieldError("min_risers", "must be >= 1");
  if (min_cluster_footfalls < 1) throw FieldError("min_cluster_footfalls", "must be >= 1");
  if (!(width_margin >= 0.0)) throw FieldError("width_margin", "must be >= 0");
}

std::vector<FootfallStaircase> StairsFromFootfalls(const std::vector<Footfall>& footfalls, const FootfallStairsSettings& settings) {
  settings.Validate();
  for (std::size_t i = 0; i < footfalls.size(); ++i) {
    if (!footfalls[i].position.allFinite() || !std::isfinite(footfalls[i].t)) {
      throw std::invalid_argument("StairsFromFootfalls: footfall " + std::to_string(i) + " is not finite");
    }
  }
  const FootfallGrid grid(footfalls, settings.max_depth);
  // 1. Candidate pairs: for every footfall, the nearest higher and the nearest lower footfall
  // that look like one step over a riser with nothing between.
  std::vector<Pair> pairs;
  std::vector<std::pair<double, int>> up, down;
  for (int a = 0; a < static_cast<int>(footfalls.size()); ++a) {
    const Eigen::Vector3d& pa = footfalls[static_cast<std::size_t>(a)].position;
    up.clear();
    down.clear();
    grid.ForNeighbours(pa, [&](int b) {
      const Eigen::Vector3d& pb = footfalls[static_cast<std::size_t>(b)].position;
      const double d = (pb - pa).head<2>().norm();
      if (d < settings.min_depth || d > settings.max_depth) return;
      const double dz = pb.z() - pa.z();
      if (dz >= settings.min_rise && dz <= settings.max_rise) up.emplace_back(d, b);
      if (-dz >= settings.min_rise && -dz <= settings.max_rise) down.emplace_back(d, b);
    });
    for (auto* list : {&up, &down}) {
      std::sort(list->begin(), list->end());
      for (const auto& [d, b] : *list) {
        if (Intervened(footfalls, grid, a, b, settings.corridor)) continue;
        Pair p;
        p.low = list == &up ? a : b;
        p.high = list == &up ? b : a;
        p.direction = (footfalls[static_cast<std::size_t>(p.high)].position - footfalls[static_cast<std::size_t>(p.low)].position).head<2>().normalized();
        pairs.push_back(p);
        break;
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return std::tie(x.low, x.high) < std::tie(y.low, y.high); });
  pairs.erase(std::unique(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.low == y.low && x.high == y.high; }), pairs.end());

  // 2. Staircases: pairs that share a footfall and agree in direction.
  std::vector<std::vector<int>> incident(footfalls.size());
  for (int i = 0; i < static_cast<int>(pairs.size()); ++i) {
    incident[static_cast<std::size_t>(pairs[static_cast<std::size_t>(i)].low)].push_back(i);
    incident[static_cast<std::size_t>(pairs[static_cast<std::size_t>(i)].high)].push_back(i);
  }
  // Two pairs are one staircase when they agree in direction and have ends on the same tread:
  // a shared footfall (one foot climbing on) or footfalls side by side at one height (the other
  // foot, or the next step of the climb).
  UnionFind groups(pairs.size());
  const double cos_tol = std::cos(settings.direction_tolerance);
  const auto agree = [&](int i, int j) {
    return pairs[static_cast<std::size_t>(i)].direction.dot(pairs[static_cast<std::size_t>(j)].direction) >= cos_tol;
  };
  for (const auto& list : incident) {
    for (std::size_t i = 0; i < list.size(); ++i) {
      for (std::size_t j = i + 1; j < list.size(); ++j) {
        if (agree(list[i], list[j])) groups.Join(list[i], list[j]);
      }
    }
  }
  for (int i = 0; i < static_cast<int>(pairs.size()); ++i) {
    for (int end : {pairs[static_cast<std::size_t>(i)].low, pairs[static_cast<std::size_t>(i)].high}) {
      const Eigen::Vector3d& pe = footfalls[static_cast<std::size_t>(end)].position;
      grid.ForNeighbours(pe, [&](int c) {
        const Eigen::Vector3d& pc = footfalls[static_cast<std::size_t>(c)].position;
        if (std::abs(pc.z() - pe.z()) > settings.height_tolerance || (pc - pe).head<2>().norm() > settings.max_depth) return;
        for (int j : incident[static_cast<std::size_t>(c)]) {
          if (agree(i, j)) groups.Join(i, j);
        }
      });
    }
  }
  std::unordered_map<int, std::vector<int>> members;  // group -> footfalls
  std::unordered_map<int, std::vector<Eigen::Vector2d>> directions;  // group -> pair directions
  for (int i = 0; i < static_cast<int>(pairs.size()); ++i) {
    const int g = groups.Find(i);
    members[g].push_back(pairs[static_cast<std::size_t>(i)].low);
    members[g].push_back(pairs[static_cast<std::size_t>(i)].high);
    directions[g].push_back(pairs[static_cast<std::size_t>(i)].direction);
  }

  // 3. Per staircase: clusters by height; runs of clusters a rise apart are the stairs.
  std::vector<FootfallStaircase> result;
  for (auto& member : members) {
    // Named, not a structured binding: C++17 lambdas cannot capture those (clang rejects it).
    const int group = member.first;
    std::vector<int>& ids = member.second;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::sort(ids.begin(), ids.end(), [&](int a, int b) { return footfalls[static_cast<std::size_t>(a)].position.z() < footfalls[static_cast<std::size_t>(b)].position.z(); });
    std::vector<std::vector<int>> clusters;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const double z = footfalls[static_cast<std::size_t>(ids[i])].position.z();
      if (i == 0 || z - footfalls[static_cast<std::size_t>(ids[i - 1])].position.z() > settings.height_tolerance) clusters.emplace_back();
      clusters.back().push_back(ids[i]);
    }
    const auto mean_z = [&](const std::vector<int>& c) {
      double s = 0.0;
      for (int i : c) s += footfalls[static_cast<std::size_t>(i)].position.z();
      return s / static_cast<double>(c.size());
    };
    // A lone footfall off its tread's height by a few sigma makes a cluster of its own: it joins
    // the cluster nearest in height when that is within a rise.
    for (bool merged = true; merged && clusters.size() > 1;) {
      merged = false;
      for (std::size_t i = 0; i < clusters.size(); ++i) {
        if (static_cast<int>(clusters[i].size()) >= settings.min_cluster_footfalls) continue;
        const double z = mean_z(clusters[i]);
        const double below = i > 0 ? z - mean_z(clusters[i - 1]) : std::numeric_limits<double>::infinity();
        const double above = i + 1 < clusters.size() ? mean_z(clusters[i + 1]) - z : std::numeric_limits<double>::infinity();
        if (std::min(below, above) > 0.5 * settings.max_rise) continue;
        const std::size_t into = below <= above ? i - 1 : i + 1;
        clusters[into].insert(clusters[into].end(), clusters[i].begin(), clusters[i].end());
        clusters.erase(clusters.begin() + static_cast<std::ptrdiff_t>(i));
        merged = true;
        break;
      }
    }
    std::vector<std::vector<int>> run;
    // A run of clusters a rise apart is a staircase; a cluster with too few footfalls to be a
    // tread (a stray foot on a connecting walk) ends it.
    const auto flush = [&] {
      std::vector<std::vector<int>> part;
      for (std::size_t i = 0; i <= run.size(); ++i) {
        if (i < run.size() && static_cast<int>(run[i].size()) >= settings.min_cluster_footfalls) {
          part.push_back(run[i]);
          continue;
        }
        if (static_cast<int>(part.size()) >= settings.min_risers + 1) result.push_back(BuildStaircase(footfalls, part, directions[group], settings));
        part.clear();
      }
      run.clear();
    };
    for (const auto& c : clusters) {
      if (!run.empty()) {
        const double gap = mean_z(c) - mean_z(run.back());
        if (gap < 0.5 * settings.min_rise) {  // one tread split by an unlucky gap: merge back
          run.back().insert(run.back().end(), c.begin(), c.end());
          continue;
        }
        if (gap > settings.max_rise) flush();
      }
      run.push_back(c);
    }
    flush();
  }
  // A zig-zag of pairs across one flight (left foot to right foot, tread after tread) can form a
  // thin group of its own; its footfalls mostly belong to the flight's own staircase, so it goes.
  std::sort(result.begin(), result.end(), [](const FootfallStaircase& a, const FootfallStaircase& b) {
    return a.footfalls.size() > b.footfalls.size();
  });
  std::vector<char> taken(footfalls.size(), 0);
  std::vector<FootfallStaircase> kept;
  for (FootfallStaircase& s : result) {
    const auto shared = std::count_if(s.footfalls.begin(), s.footfalls.end(), [&](int i) { return taken[static_cast<std::size_t>(i)] != 0; });
    if (2 * shared > static_cast<long>(s.footfalls.size())) continue;
    for (int i : s.footfalls) taken[static_cast<std::size_t>(i)] = 1;
    kept.push_back(std::move(s));
  }
  std::sort(kept.begin(), kept.end(), [](const FootfallStaircase& a, const FootfallStaircase& b) { return a.t_begin < b.t_begin; });
  return kept;
}

}  // namespace stairplan
