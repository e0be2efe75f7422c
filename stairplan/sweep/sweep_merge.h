// Sweep CSVs as tables of lines keyed by point index: a manifest, a column header, one line per
// point. Shards are merged only when they are the complete, non-overlapping shards of one sweep,
// and a journal (a CSV appended to as points finish) is read back for `sweep --resume`.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "stairplan/sweep/sweep_manifest.h"

namespace stairplan {

/// A sweep CSV taken apart.
struct SweepTableText {
  SweepManifest manifest;  ///< the '#' lines
  std::string header;                ///< the column header line
  std::map<int, std::string> lines;  ///< data lines (no newline) by point index

  /// Manifest, header and the lines in point order: the canonical CSV.
  std::string ToCsv() const;
};

/// Reads a sweep CSV. With `journal`, a last line without its newline (cut off by a kill) is
/// dropped; otherwise it is an error. Throws std::invalid_argument naming `file` (and the line)
/// when the manifest or header is missing, a line is not a row, or a point appears twice.
SweepTableText ReadSweepTable(const std::string& text, const std::string& file, bool journal = false);

/// Merges the shards of one sweep into the whole sweep's CSV (its manifest's shard "0/1").
/// Throws std::invalid_argument naming the file and what is wrong when the manifests or headers
/// differ (a different grid, robot, settings or version), the shard counts differ, a shard is
/// given twice or missing, a plans table lacks a point of its shard, or a line holds a point that
/// is not its shard's.
std::string MergeSweepCsv(const std::vector<std::pair<std::string, std::string>>& files_and_texts);

}  // namespace stairplan
