#include "stairplan/perception/height_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "stairplan/geometry/field_error.h"

namespace stairplan {
namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}

const char* ToString(CellState state) {
  switch (state) {
    case CellState::kUnknown: return "unknown";
    case CellState::kMeasured: return "measured";
    case CellState::kOccluded: return "occluded";
    case CellState::kSmoothed: return "smoothed";
    case CellState::kPoor: return "poor";
  }
  return "invalid";
}

void HeightMapSettings::Validate() const {
  if (!(resolution >= 0.002 && resolution <= 1.0)) throw FieldError("resolution", "must be in [0.002, 1] m");
  if (!(top_band >= 0.0 && top_band <= 1.0)) throw FieldError("top_band", "must be in [0, 1] m");
  if (max_cells < 1) throw FieldError("max_cells", "must be positive");
}

HeightMap::HeightMap(const Eigen::Vector2d& origin, double resolution, int nx, int ny)
    : origin_(origin), resolution_(resolution), nx_(nx), ny_(ny) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) throw std::invalid_argument("HeightMap: resolution must be positive");
  if (nx < 1 || ny < 1) throw std::invalid_argument("HeightMap: nx and ny must be >= 1");
  if (!origin.allFinite()) throw std::invalid_argument("HeightMap: origin must be finite");
  const auto n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  height_.assign(n, kNaN);
  spread_.assign(n, 0.0f);
  top_above_.assign(n, 0.0f);
  count_.assign(n, 0);
  state_.assign(n, CellState::kUnknown);
}

HeightMap HeightMap::FromCloud(const PointCloud& cloud, const HeightMapSettings& settings) {
  settings.Validate();
  if (cloud.empty()) throw std::invalid_argument("HeightMap::FromCloud: the point cloud is empty");
  const Eigen::Vector3d lo = cloud.Min(), hi = cloud.Max();
  const double res = settings.resolution;
  const double nx = std::floor((hi.x() - lo.x()) / res) + 1.0;
  const double ny = std::floor((hi.y() - lo.y()) / res) + 1.0;
  if (nx * ny > settings.max_cells) {
    throw std::invalid_argument("HeightMap::FromCloud: the cloud spans " + std::to_string(hi.x() - lo.x()) + " x " +
                                std::to_string(hi.y() - lo.y()) + " m, more than max_cells at this resolution");
  }
  HeightMap map(lo.head<2>(), res, static_cast<int>(nx), static_cast<int>(ny));
  std::vector<float> top(map.height_.size(), -std::numeric_limits<float>::infinity());
  std::vector<float> bottom(map.height_.size(), std::numeric_limits<float>::infinity());
  std::vector<std::size_t> cell_of(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    const int ix = std::min(map.nx_ - 1, static_cast<int>((p.x() - lo.x()) / res));
    const int iy = std::min(map.ny_ - 1, static_cast<int>((p.y() - lo.y()) / res));
    const std::size_t c = map.Index(ix, iy);
    cell_of[i] = c;
    top[c] = std::max(top[c], static_cast<float>(p.z()));
    bottom[c] = std::min(bottom[c], static_cast<float>(p.z()));
    if (map.count_[c] < 65535) ++map.count_[c];
  }
  std::vector<double> sum(map.height_.size(), 0.0);
  std::vector<int> in_band(map.height_.size(), 0);
  const auto band = static_cast<float>(settings.top_band);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::size_t c = cell_of[i];
    const auto z = static_cast<float>(cloud.points[i].z());
    if (z >= top[c] - band) {
      sum[c] += z;
      ++in_band[c];
    }
  }
  for (std::size_t c = 0; c < map.height_.size(); ++c) {
    if (in_band[c] == 0) continue;
    map.height_[c] = static_cast<float>(sum[c] / in_band[c]);
    map.spread_[c] = top[c] - bottom[c];
    map.top_above_[c] = top[c] - map.height_[c];
    map.state_[c] = CellState::kMeasured;
  }
  return map;
}

void HeightMap::Set(int ix, int iy, float height, CellState state, float spread) {
  if (!Inside(ix, iy)) throw std::out_of_range("HeightMap::Set: cell outside the grid");
  const std::size_t c = Index(ix, iy);
  height_[c] = height;
  state_[c] = state;
  spread_[c] = spread;
  top_above_[c] = 0.0f;
}

Eigen::Vector2d HeightMap::CellCenter(int ix, int iy) const {
  return origin_ + resolution_ * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

bool HeightMap::CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const {
  if (!p.allFinite()) return false;
  const double fx = std::floor((p.x() - origin_.x()) / resolution_);
  const double fy = std::floor((p.y() - origin_.y()) / resolution_);
  if (fx < 0 || fy < 0 || fx >= nx_ || fy >= ny_) return false;
  *ix = static_cast<int>(fx);
  *iy = static_cast<int>(fy);
  return true;
}

double HeightMap::HeightAt(double x, double y) const {
  int ix = 0, iy = 0;
  if (!CellOf(Eigen::Vector2d(x, y), &ix, &iy)) return std::numeric_limits<double>::quiet_NaN();
  return height(ix, iy);
}

int HeightMap::CountState(CellState state) const {
  return static_cast<int>(std::count(state_.begin(), state_.end(), state));
}

}  // namespace stairplan
