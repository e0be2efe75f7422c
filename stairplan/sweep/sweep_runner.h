// Running a sweep: each grid point planned and validated by an evaluator, on K threads, with the
// rows in point order whatever the thread count; CSV output, merging of shards, an SVG heatmap.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "stairplan/planning/plan_gait.h"
#include "stairplan/sweep/sweep_grid.h"

namespace stairplan {

/// The outcome at one grid point.
struct SweepRow {
  SweepPoint point;  ///< the grid point
  /// "valid", "invalid" (plan found, validation failed), "infeasible", "bad_stairs", or "failed"
  /// (the evaluator threw; `reason` holds its message)
  std::string status;
  std::string reason;       ///< the first violation or why there is no plan; empty when valid
  double cadence_s = 0.0;  ///< the chosen controller's swing duration [s]
  int footsteps = 0;  ///< footsteps in the plan
  std::optional<Gait> gait;  ///< the gait planned (with `--gait auto`, the one taken); none when unknown
  double min_clearance_m = std::numeric_limits<double>::quiet_NaN();         ///< blank in CSV when unknown
  /// Smallest COM margin of the validation; blank in CSV when unknown [m].
  double min_stability_margin_m = std::numeric_limits<double>::quiet_NaN();
  double plan_us = 0.0;     ///< not deterministic: only written with times
  double validate_us = 0.0;  ///< not deterministic: only written with times
};

/// Plans and validates one point. Must be thread-safe; what it throws becomes a "failed" row.
using PointEvaluator = std::function<SweepRow(const SweepPoint&)>;

/// Called after each finished point with (done, total); from worker threads, serialised.
using SweepProgress = std::function<void(int done, int total)>;

/// Called with each finished row as soon as it is known (before `progress`); serialised.
using SweepRowSink = std::function<void(const SweepRow& row)>;

/// Evaluates the points of `shard` on `threads` threads; rows are in point order. A point whose
/// evaluation throws is a row of status "failed" with the message, and the sweep goes on.
std::vector<SweepRow> RunSweep(const std::vector<SweepPoint>& points, const PointEvaluator& evaluate, int threads,
                               const Shard& shard = {}, const SweepProgress& progress = nullptr,
                               const SweepRowSink& on_row = nullptr);

/// `evaluate(point)`, or a row of status "failed" whose reason is what it threw.
SweepRow EvaluateGuarded(const PointEvaluator& evaluate, const SweepPoint& point);

/// The CSV header line (without newline); `with_times` adds plan_us and validate_us.
std::string SweepCsvHeader(bool with_times);
/// The CSV text of `rows` with header; byte-identical for identical results.
std::string SweepToCsv(const std::vector<SweepRow>& rows, bool with_times);
/// One row's CSV line, without newline.
std::string SweepCsvLine(const SweepRow& row, bool with_times);
/// The fields of a CSV line, quotes (and "" inside them) removed.
std::vector<std::string> CsvLineFields(const std::string& line);
/// A row from its CSV line (with or without the time columns, and without the gait column of rows
/// written before it: no gait then); throws std::invalid_argument.
SweepRow SweepRowFromCsvLine(const std::string& line);

/// The rows of a sweep CSV (SweepToCsv's or a merge's, '#' manifest lines skipped; times read when
/// present), so a merged sweep can be summarised. Throws std::invalid_argument naming `file` and
/// the line when a row is malformed.
std::vector<SweepRow> SweepRowsFromCsv(const std::string& text, const std::string& file);

/// A rise x run heatmap per direction with the building-code boxes drawn.
std::string SweepHeatmapSvg(const std::vector<SweepRow>& rows, const SweepGrid& grid);

}  // namespace stairplan
