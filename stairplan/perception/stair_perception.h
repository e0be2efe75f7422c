// Perception end to end (US 2020/0324412 A1 ("Robotically negotiating stairs") claim 1, step
// regions from image data): a point cloud becomes a height map with its gaps filled, the stair
// tracker's model, and the constrained map the planners use. One call for `stairplan plan --cloud`
// and `stairplan map`.
#pragma once

#include <optional>

#include "stairplan/perception/gap_fill.h"
#include "stairplan/perception/height_map.h"
#include "stairplan/perception/map_from_height_map.h"
#include "stairplan/perception/point_cloud.h"
#include "stairplan/perception/stair_tracker.h"

namespace stairplan {

/// The settings of each stage of PerceiveStairs().
struct StairPerceptionSettings {
  HeightMapSettings height_map;  ///< binning the cloud
  GapFillSettings gap_fill;  ///< filling the height map's holes
  StairTrackerSettings tracker;  ///< fitting the staircase
  MapFromHeightMapSettings regions;  ///< collision regions from the data
};

/// What PerceiveStairs() found, stage by stage.
struct StairPerception {
  HeightMap height_map;                  ///< with gaps filled
  GapFillReport gap_fill;  ///< what gap filling did
  StairFit fit;                          ///< the tracker's answer (found or why not)
  std::optional<PerceivedStairs> stairs; ///< the Staircase and ConstrainedMap, when stairs were found
};

/// Runs the whole pipeline. Throws std::invalid_argument for an empty cloud or bad settings;
/// a cloud that is not stairs gives `stairs` empty and `fit.reason` says why.
StairPerception PerceiveStairs(const PointCloud& cloud, const StairPerceptionSettings& settings = {});

}  // namespace stairplan
