// The summary of a feasibility atlas (`stairplan sweep --robots ...`): for each robot and
// direction, how much of the rise x run grid it can climb and where that region ends.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "stairplan/sweep/sweep_runner.h"

namespace stairplan {

/// One robot's feasible region in one direction.
struct AtlasEntry {
  std::string robot;  ///< the robot's name
  TravelDirection direction = TravelDirection::kUp;  ///< up or down
  int points = 0;  ///< grid points in this direction
  int valid = 0;  ///< of which valid
  bool connected = true;          ///< the valid points form one area in every slice
  double steepest_rise = 0.0;     ///< the valid point of the largest rise/run (0 when none)
  double steepest_run = 0.0;  ///< the run of that steepest valid point
  double highest_rise = 0.0;      ///< the largest valid rise, at any run
  double shortest_run = 0.0;      ///< the shortest valid run, at any rise
};

/// An entry per robot (in the given order) and direction of `grid`.
std::vector<AtlasEntry> SummariseAtlas(const std::vector<std::pair<std::string, std::vector<SweepRow>>>& robots,
                                       const SweepGrid& grid);

/// The summary as a Markdown table, headed by the grid it covers.
std::string SweepAtlasMarkdown(const std::vector<std::pair<std::string, std::vector<SweepRow>>>& robots,
                               const SweepGrid& grid);

}  // namespace stairplan
