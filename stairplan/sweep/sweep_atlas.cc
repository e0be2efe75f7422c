#include "stairplan/sweep/sweep_atlas.h"

#include <cmath>
#include <cstdio>

#include "stairplan/sweep/sweep_manifest.h"
#include "stairplan/sweep/sweep_region.h"

namespace stairplan {
namespace {

AtlasEntry Summarise(const std::string& robot, const std::vector<SweepRow>& all, TravelDirection direction) {
  AtlasEntry e;
  e.robot = robot;
  e.direction = direction;
  std::vector<SweepRow> rows;
  for (const SweepRow& r : all) {
    if (r.point.direction == direction) rows.push_back(r);
  }
  e.points = static_cast<int>(rows.size());
  for (const SweepRow& r : rows) {
    if (r.status != "valid") continue;
    const bool first = e.valid++ == 0;
    if (first || r.point.rise * e.steepest_run > e.steepest_rise * r.point.run) {
      e.steepest_rise = r.point.rise;
      e.steepest_run = r.point.run;
    }
    if (first || r.point.rise > e.highest_rise) e.highest_rise = r.point.rise;
    if (first || r.point.run < e.shortest_run) e.shortest_run = r.point.run;
  }
  for (const SweepRegion& region : AnalyseSweepRegions(rows)) e.connected = e.connected && region.Connected();
  return e;
}

}  // namespace

std::vector<AtlasEntry> SummariseAtlas(const std::vector<std::pair<std::string, std::vector<SweepRow>>>& robots,
                                       const SweepGrid& grid) {
  std::vector<AtlasEntry> entries;
  for (const auto& [robot, rows] : robots) {
    for (TravelDirection d : grid.directions) entries.push_back(Summarise(robot, rows, d));
  }
  return entries;
}

std::string SweepAtlasMarkdown(const std::vector<std::pair<std::string, std::vector<SweepRow>>>& robots,
                               const SweepGrid& grid) {
  std::string md = "Feasibility atlas: rise " + AxisText(grid.rise) + " m x run " + AxisText(grid.run) +
                   " m (A:B:N), " + AxisText(grid.steps) + " steps, nosing " + AxisText(grid.nosing) + " m\n\n" +
                   "| robot | direction | valid / points | one connected area | steepest valid rise / run (pitch) | "
                   "highest valid rise | shortest valid run |\n|---|---|---|---|---|---|---|\n";
  char line[320];
  for (const AtlasEntry& e : SummariseAtlas(robots, grid)) {
    std::snprintf(line, sizeof(line), "| %s | %s | %d / %d | %s |", e.robot.c_str(), ToString(e.direction), e.valid,
                  e.points, e.valid == 0 ? "-" : e.connected ? "yes" : "no");
    md += line;
    if (e.valid == 0) {
      md += " - | - | - |\n";
      continue;
    }
    std::snprintf(line, sizeof(line), " %.3f / %.3f m (%.1f deg) | %.3f m | %.3f m |\n", e.steepest_rise,
                  e.steepest_run, std::atan2(e.steepest_rise, e.steepest_run) * 180.0 / M_PI, e.highest_rise,
                  e.shortest_run);
    md += line;
  }
  return md;
}

}  // namespace stairplan
