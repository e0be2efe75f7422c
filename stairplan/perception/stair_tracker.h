// The stair tracker (US 2020/0324412 A1 ("Robotically negotiating stairs") [0071]): fits a regular
// staircase to a noisy point cloud by leaning on the structure every staircase shares: parallel
// edges at a constant run, flat treads at a constant rise. Terrain that does not fit (a ramp, a
// flat floor, a single box) is rejected with the reason, and a fit reports how well the model
// explains the data.
#pragma once

#include <string>
#include <vector>

#include "stairplan/perception/point_cloud.h"
#include "stairplan/geometry/stair_model.h"

namespace stairplan {

/// The stair tracker's ranges and tolerances: what it accepts as stairs.
struct StairTrackerSettings {
  double min_rise = 0.08;   ///< [m]
  double max_rise = 0.30;   ///< [m]
  double min_run = 0.15;    ///< [m]
  double max_run = 0.60;    ///< [m]
  int min_risers = 2;       ///< fewer edges than this are not stairs (a kerb, a box)
  double cell = 0.02;       ///< height-map cell used to find the stairs' heading [m]
  double bin = 0.01;        ///< profile bin along the stairs' direction [m]
  /// How far past an edge the riser face and lip underside can show below the nosing's top [m].
  double nosing_reach = 0.04;
  /// Profile heights within a plateau spread less than this; a wider spread means no plateau [m].
  double plateau_spread = 0.04;
  /// Share of the profile that must lie on plateaus (a ramp has none).
  double min_plateau_fraction = 0.6;
  double max_level_residual = 0.04;  ///< a level further than this from the regular rise rejects [m]
  double max_edge_residual = 0.05;   ///< an edge further than this from the regular run rejects [m]

  /// Throws FieldError naming the field.
  void Validate() const;
};

/// The tracker's answer: the fitted stairs and how well they explain the data, or why there are none.
struct StairFit {
  bool found = false;  ///< true when the cloud is stairs
  std::string reason;      ///< why the cloud is not stairs (empty when found)
  StairModel model;        ///< the stairs, valid when found
  std::vector<double> level_residuals;  ///< measured minus fitted level heights, lowest first [m]
  std::vector<double> edge_residuals;   ///< measured minus fitted edge positions, lowest first [m]
  double level_rms = 0.0;  ///< [m]
  double edge_rms = 0.0;   ///< [m]
  double point_rms = 0.0;  ///< tread points' heights against the model [m]
  int tread_points = 0;    ///< points used for point_rms
};

/// Fits a staircase to the cloud (world frame, z up). Throws std::invalid_argument for an empty
/// cloud; anything else that is not stairs is a StairFit with found == false and a reason.
StairFit FitStairs(const PointCloud& cloud, const StairTrackerSettings& settings = {});

}  // namespace stairplan
