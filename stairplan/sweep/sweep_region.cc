#include "stairplan/sweep/sweep_region.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <tuple>

namespace stairplan {
namespace {

// One slice's rows on its grid: cell (i, j) is the i-th smallest rise and the j-th smallest run.
class SliceGrid {
 public:
  explicit SliceGrid(const std::vector<const SweepRow*>& rows) {
    for (const SweepRow* r : rows) {
      rises_.push_back(r->point.rise);
      runs_.push_back(r->point.run);
    }
    Unique(rises_);
    Unique(runs_);
    cells_.assign(rises_.size() * runs_.size(), nullptr);
    for (const SweepRow* r : rows) cells_[Cell(Index(rises_, r->point.rise), Index(runs_, r->point.run))] = r;
  }

  int rises() const { return static_cast<int>(rises_.size()); }
  int runs() const { return static_cast<int>(runs_.size()); }
  const SweepRow* at(int i, int j) const { return cells_[Cell(i, j)]; }
  bool Valid(int i, int j) const { return at(i, j) != nullptr && at(i, j)->status == "valid"; }

  // Connected areas of valid cells (flood fill over rise and run neighbours).
  int Areas() const {
    std::vector<bool> seen(cells_.size(), false);
    int areas = 0;
    for (int i = 0; i < rises(); ++i) {
      for (int j = 0; j < runs(); ++j) {
        if (!Valid(i, j) || seen[Cell(i, j)]) continue;
        ++areas;
        Fill(i, j, seen);
      }
    }
    return areas;
  }

  // The valid cell nearest to (i, j) that is at least as steep (rise index >= i, run index <= j),
  // or nullptr.
  const SweepRow* SteeperValid(int i, int j) const {
    const SweepRow* best = nullptr;
    int best_steps = 0;
    for (int a = i; a < rises(); ++a) {
      for (int b = 0; b <= j; ++b) {
        const int steps = (a - i) + (j - b);
        if (!Valid(a, b) || (best != nullptr && steps >= best_steps)) continue;
        best = at(a, b);
        best_steps = steps;
      }
    }
    return best;
  }

 private:
  static void Unique(std::vector<double>& values) {
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
  }
  static int Index(const std::vector<double>& values, double v) {
    return static_cast<int>(std::lower_bound(values.begin(), values.end(), v) - values.begin());
  }
  std::size_t Cell(int i, int j) const { return static_cast<std::size_t>(i) * runs_.size() + static_cast<std::size_t>(j); }

  void Fill(int i0, int j0, std::vector<bool>& seen) const {
    std::vector<std::pair<int, int>> stack = {{i0, j0}};
    seen[Cell(i0, j0)] = true;
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= rises() || b >= runs() || !Valid(a, b) || seen[Cell(a, b)]) continue;
        seen[Cell(a, b)] = true;
        stack.emplace_back(a, b);
      }
    }
  }

  std::vector<double> rises_, runs_;
  std::vector<const SweepRow*> cells_;
};

SweepRegion AnalyseSlice(const std::vector<const SweepRow*>& rows) {
  SweepRegion region;
  region.direction = rows.front()->point.direction;
  region.steps = rows.front()->point.steps;
  region.nosing = rows.front()->point.nosing;
  region.points = static_cast<int>(rows.size());
  const SliceGrid grid(rows);
  region.areas = grid.Areas();
  for (int i = 0; i < grid.rises(); ++i) {
    for (int j = 0; j < grid.runs(); ++j) {
      if (grid.Valid(i, j)) ++region.valid;
      if (grid.at(i, j) == nullptr || grid.Valid(i, j)) continue;
      if (const SweepRow* steeper = grid.SteeperValid(i, j)) region.breaks.push_back({*grid.at(i, j), steeper->point});
    }
  }
  std::sort(region.breaks.begin(), region.breaks.end(),
            [](const SteepnessBreak& a, const SteepnessBreak& b) { return a.failed.point.index < b.failed.point.index; });
  return region;
}

std::string Metres(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", v);
  return buffer;
}

}  // namespace

std::vector<SweepRegion> AnalyseSweepRegions(const std::vector<SweepRow>& rows) {
  using Key = std::tuple<int, int, double>;  // direction, steps, nosing
  std::vector<Key> order;
  std::map<Key, std::vector<const SweepRow*>> slices;
  for (const SweepRow& r : rows) {
    const Key key{static_cast<int>(r.point.direction), r.point.steps, r.point.nosing};
    auto& slice = slices[key];
    if (slice.empty()) order.push_back(key);
    slice.push_back(&r);
  }
  std::vector<SweepRegion> regions;
  for (const Key& key : order) regions.push_back(AnalyseSlice(slices[key]));
  return regions;
}

std::string SweepRegionsToText(const std::vector<SweepRegion>& regions) {
  std::ostringstream out;
  for (const SweepRegion& r : regions) {
    out << ToString(r.direction) << ", " << r.steps << " steps, nosing " << Metres(r.nosing) << " m: " << r.valid << "/"
        << r.points << " valid; ";
    if (r.areas == 0) {
      out << "no valid point";
    } else {
      out << (r.Connected() ? "one connected area" : std::to_string(r.areas) + " separate areas");
    }
    out << "; steeper stairs fail first: "
        << (r.SteeperFailFirst() ? "yes" : "no, " + std::to_string(r.breaks.size()) + " points break it") << "\n";
    for (const SteepnessBreak& b : r.breaks) {
      out << "  rise " << Metres(b.failed.point.rise) << " run " << Metres(b.failed.point.run) << ": " << b.failed.status
          << (b.failed.reason.empty() ? "" : " (" + b.failed.reason + ")") << ", but rise "
          << Metres(b.steeper_valid.rise) << " run " << Metres(b.steeper_valid.run) << " is valid\n";
    }
  }
  return out.str();
}

}  // namespace stairplan
