#include "stairplan/perception/stair_perception.h"

namespace stairplan {

StairPerception PerceiveStairs(const PointCloud& cloud, const StairPerceptionSettings& settings) {
  StairPerception out;
  out.height_map = HeightMap::FromCloud(cloud, settings.height_map);
  out.gap_fill = FillGaps(out.height_map, settings.gap_fill);
  out.fit = FitStairs(cloud, settings.tracker);
  if (out.fit.found) out.stairs = ConstrainedMapFromHeightMap(out.height_map, out.fit.model, settings.regions);
  return out;
}

}  // namespace stairplan
