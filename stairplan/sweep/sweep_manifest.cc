#include "stairplan/sweep/sweep_manifest.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "stairplan/version.h"

namespace stairplan {
namespace {

constexpr char kTitle[] = "# stairplan sweep manifest";

const char* TableName(SweepTable table) { return table == SweepTable::kPlans ? "plans" : "physics"; }

std::string ManifestNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", v);
  return buffer;
}

std::string DirectionsText(const std::vector<TravelDirection>& directions) {
  std::string text;
  for (TravelDirection d : directions) text += (text.empty() ? "" : ",") + std::string(ToString(d));
  return text;
}

}  // namespace

std::string AxisText(const SweepAxis& axis) {
  if (axis.count == 1) return ManifestNumber(axis.lo);
  return ManifestNumber(axis.lo) + ":" + ManifestNumber(axis.hi) + ":" + std::to_string(axis.count);
}

SweepManifest SweepManifest::Current(SweepTable table, const SweepGrid& grid, const std::string& robot,
                                     const std::string& settings, const Shard& shard) {
  SweepManifest m;
  m.table = table;
  m.grid = grid;
  m.robot = robot;
  m.settings = settings;
  m.shard = shard;
  m.version = kVersion;
  m.schema = kSchemaVersion;
  return m;
}

std::vector<std::pair<std::string, std::string>> SweepManifest::Fields() const {
  return {{"table", TableName(table)},
          {"version", version},
          {"schema", std::to_string(schema)},
          {"robot", robot},
          {"rise", AxisText(grid.rise)},
          {"run", AxisText(grid.run)},
          {"nosing", AxisText(grid.nosing)},
          {"steps", AxisText(grid.steps)},
          {"directions", DirectionsText(grid.directions)},
          {"facing", ToString(grid.facing)},
          {"settings", settings},
          {"shard", std::to_string(shard.index) + "/" + std::to_string(shard.count)}};
}

std::string SweepManifest::ToText() const {
  std::string text = std::string(kTitle) + "\n";
  for (const auto& [key, value] : Fields()) text += "# " + key + ": " + value + "\n";
  return text;
}

SweepManifest SweepManifest::FromText(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kTitle) {
    throw std::invalid_argument(file + ":1: no sweep manifest (a CSV of an older stairplan, or not a sweep CSV)");
  }
  std::map<std::string, std::string> values;
  for (int number = 2; std::getline(in, line) && line.rfind("# ", 0) == 0; ++number) {
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) throw std::invalid_argument(file + ":" + std::to_string(number) + ": malformed manifest line");
    values[line.substr(2, colon - 2)] = line.substr(colon + 2);
  }
  const auto get = [&](const std::string& key) {
    const auto it = values.find(key);
    if (it == values.end()) throw std::invalid_argument(file + ": manifest: no '" + key + "'");
    return it->second;
  };
  SweepManifest m;
  try {
    const std::string table = get("table");
    if (table != "plans" && table != "physics") throw std::invalid_argument("table: unknown '" + table + "'");
    m.table = table == "plans" ? SweepTable::kPlans : SweepTable::kPhysics;
    m.version = get("version");
    m.schema = std::stoi(get("schema"));
    m.robot = get("robot");
    m.grid.rise = SweepAxis::Parse(get("rise"), "rise");
    m.grid.run = SweepAxis::Parse(get("run"), "run");
    m.grid.nosing = SweepAxis::Parse(get("nosing"), "nosing");
    m.grid.steps = SweepAxis::Parse(get("steps"), "steps");
    m.grid.directions = ParseDirections(get("directions"), "directions");
    const std::string facing = get("facing");
    if (facing != ToString(Facing::kForward) && facing != ToString(Facing::kBackward)) {
      throw std::invalid_argument("facing: unknown '" + facing + "'");
    }
    m.grid.facing = facing == ToString(Facing::kForward) ? Facing::kForward : Facing::kBackward;
    m.settings = get("settings");
    m.shard = Shard::Parse(get("shard"), "shard");
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    if (message.rfind(file, 0) == 0) throw;
    throw std::invalid_argument(file + ": manifest: " + message);
  }
  return m;
}

std::string SweepManifest::Difference(const SweepManifest& other) const {
  const auto mine = Fields(), theirs = other.Fields();
  for (std::size_t i = 0; i < mine.size(); ++i) {
    if (mine[i].first == "shard" || mine[i].second == theirs[i].second) continue;
    return mine[i].first + ": '" + mine[i].second + "' vs '" + theirs[i].second + "'";
  }
  return "";
}

}  // namespace stairplan
