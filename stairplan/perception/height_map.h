// A 2.5-D elevation grid built from a point cloud: float cells with NaN for unknown, as in
// grid_map's elevation layer, plus per-cell bookkeeping (how many points, their vertical spread,
// and whether a value was measured or inferred by gap filling). Cell (ix, iy) covers
// [x0 + ix*res, x0 + (ix+1)*res) x [y0 + iy*res, y0 + (iy+1)*res); ix runs with +x, iy with +y.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "stairplan/perception/point_cloud.h"

namespace stairplan {

/// Where a cell's height came from.
enum class CellState : std::uint8_t {
  kUnknown,   ///< no data and not inferred: height is NaN
  kMeasured,  ///< from points in the cell
  kOccluded,  ///< hidden behind a near-far contrast: filled flat (US 2020/0324412 [0042])
  kSmoothed,  ///< missing without contrast: filled smoothly
  kPoor,      ///< filled smoothly but far from any data: not to be trusted for stepping
};
/// Returns "unknown", "measured", "occluded", "smoothed" or "poor".
const char* ToString(CellState state);

/// How a cloud is binned into a HeightMap.
struct HeightMapSettings {
  double resolution = 0.02;  ///< cell size [m]
  /// A cell's height is the mean of its points within this band below its highest point, so the
  /// top of a riser or nosing wins over the face below it without taking the noisiest point [m].
  double top_band = 0.015;
  int max_cells = 16'000'000;  ///< refuse clouds whose extent would need more cells

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// A 2.5-D elevation grid with per-cell bookkeeping (see the file's top comment for the cell layout).
class HeightMap {
 public:
  HeightMap() = default;
  /// An all-unknown grid of nx x ny cells whose first cell's corner is `origin`.
  HeightMap(const Eigen::Vector2d& origin, double resolution, int nx, int ny);
  /// Bins the cloud's points. Throws std::invalid_argument for an empty cloud or a too-large extent.
  static HeightMap FromCloud(const PointCloud& cloud, const HeightMapSettings& settings = {});

  /// Number of cells along x.
  int nx() const { return nx_; }
  /// Number of cells along y.
  int ny() const { return ny_; }
  /// Cell size [m].
  double resolution() const { return resolution_; }
  /// The corner of cell (0, 0) [m].
  const Eigen::Vector2d& origin() const { return origin_; }
  /// True when (ix, iy) is a cell of the grid.
  bool Inside(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_; }

  /// The cell's height: NaN when unknown [m].
  float height(int ix, int iy) const { return height_[Index(ix, iy)]; }
  /// Where the cell's height came from.
  CellState state(int ix, int iy) const { return state_[Index(ix, iy)]; }
  /// Highest minus lowest point in the cell (0 for inferred cells) [m].
  float spread(int ix, int iy) const { return spread_[Index(ix, iy)]; }
  /// The highest point in the cell (the height itself for inferred cells) [m].
  float top(int ix, int iy) const { return height_[Index(ix, iy)] + top_above_[Index(ix, iy)]; }
  /// Number of points binned into the cell (0 for inferred cells).
  int count(int ix, int iy) const { return count_[Index(ix, iy)]; }
  /// Sets a cell's height and state (tests and gap filling build maps this way).
  void Set(int ix, int iy, float height, CellState state, float spread = 0.0f);

  /// The centre of cell (ix, iy) in the xy plane [m].
  Eigen::Vector2d CellCenter(int ix, int iy) const;
  /// The cell containing p; false when p is outside the grid.
  bool CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const;
  /// The height of the cell containing (x, y); NaN outside or unknown.
  double HeightAt(double x, double y) const;
  /// Number of cells in each state.
  int CountState(CellState state) const;

 private:
  std::size_t Index(int ix, int iy) const { return static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix); }

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double resolution_ = 0.02;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<float> height_;
  std::vector<float> spread_;
  std::vector<float> top_above_;  // highest point minus height
  std::vector<std::uint16_t> count_;
  std::vector<CellState> state_;
};

}  // namespace stairplan
