// A sweep's CSV written as the sweep goes: the manifest and header first, then each row appended
// and flushed as its point finishes, so a killed run loses at most the points being computed and
// `sweep --resume` continues it; at the end the file is rewritten in point order.
#pragma once

#include <fstream>
#include <map>
#include <string>

#include "stairplan/sweep/sweep_merge.h"

namespace stairplan::cli {

class SweepJournal {
 public:
  /// A journal at `path` for `manifest`'s sweep with column `header`. With `resume` and an existing
  /// file, its finished lines are kept; throws BadInput naming the file when it holds another
  /// sweep (or shard) or is not a sweep CSV. Nothing is written before Open().
  SweepJournal(std::string path, SweepManifest manifest, std::string header, bool resume);

  /// The lines kept from an earlier run, by point index.
  const std::map<int, std::string>& lines() const { return table_.lines; }
  /// Drops the kept lines of points not in `done` (they are computed again).
  void RetainOnly(const std::map<int, std::string>& done);
  /// Writes the manifest, header and kept lines, and opens the file for appending.
  void Open();
  /// Appends one finished point's line and flushes it.
  void Append(int index, const std::string& line);
  /// Rewrites the file in point order through a temporary file; returns its text.
  std::string Finish();

 private:
  std::string path_;
  SweepTableText table_;
  std::ofstream out_;
};

}  // namespace stairplan::cli
