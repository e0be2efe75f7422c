// What a sweep CSV was computed from, written as '#'-prefixed "key: value" lines before its column
// header: the grid, directions, robot, settings, shard and the versions that wrote it. Shards of
// different sweeps are never merged and a resumed run only continues its own sweep because both
// compare manifests.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "stairplan/sweep/sweep_grid.h"

namespace stairplan {

/// Which table of a sweep a CSV holds.
enum class SweepTable { kPlans, kPhysics };

/// A sweep CSV's manifest.
struct SweepManifest {
  SweepTable table = SweepTable::kPlans;  ///< plans or physics
  SweepGrid grid;  ///< the grid swept
  std::string robot;     ///< names the robot and its file's content (the CLI writes name, file, hash)
  std::string settings;  ///< every other setting the rows depend on, "key=value ..."
  Shard shard;  ///< which shard of the sweep the file holds
  std::string version;   ///< kVersion of the program that wrote it
  int schema = 0;        ///< kSchemaVersion of the program that wrote it

  /// A manifest of this program's version and schema.
  static SweepManifest Current(SweepTable table, const SweepGrid& grid, const std::string& robot,
                               const std::string& settings, const Shard& shard);

  /// The "key: value" pairs, in the order they are written.
  std::vector<std::pair<std::string, std::string>> Fields() const;
  /// The '#' lines, each ending in a newline.
  std::string ToText() const;
  /// The manifest at the start of `text`; throws std::invalid_argument naming `file` when it has
  /// none or a field is missing or malformed.
  static SweepManifest FromText(const std::string& text, const std::string& file);
  /// The first field other than the shard in which the two differ, "field: 'a' vs 'b'"; empty
  /// when they describe the same sweep.
  std::string Difference(const SweepManifest& other) const;
};

/// "A:B:N", or "V" for a single value; SweepAxis::Parse reads it back.
std::string AxisText(const SweepAxis& axis);

}  // namespace stairplan
