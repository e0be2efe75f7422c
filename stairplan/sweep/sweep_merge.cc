#include "stairplan/sweep/sweep_merge.h"

#include <sstream>
#include <stdexcept>

namespace stairplan {
namespace {

// The point index: the first field of a data line, or -1.
int LineIndex(const std::string& line) {
  const std::size_t comma = line.find(',');
  if (comma == std::string::npos || comma == 0 || comma > 9) return -1;
  for (std::size_t i = 0; i < comma; ++i) {
    if (line[i] < '0' || line[i] > '9') return -1;
  }
  return std::stoi(line.substr(0, comma));
}

std::string At(const std::string& file, int line) { return file + ":" + std::to_string(line) + ": "; }

// The indices of `shard`'s points of `grid` missing from `table`, or empty.
std::vector<int> MissingPoints(const SweepTableText& table) {
  std::vector<int> missing;
  for (const SweepPoint& p : EnumeratePoints(table.manifest.grid)) {
    if (table.manifest.shard.Holds(p.index) && table.lines.count(p.index) == 0) missing.push_back(p.index);
  }
  return missing;
}

std::string ShardText(const Shard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

}  // namespace

std::string SweepTableText::ToCsv() const {
  std::string csv = manifest.ToText() + header + "\n";
  for (const auto& [index, line] : lines) csv += line + "\n";
  return csv;
}

SweepTableText ReadSweepTable(const std::string& text, const std::string& file, bool journal) {
  SweepTableText table;
  table.manifest = SweepManifest::FromText(text, file);
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) ++number;
  ++number;
  if (line.rfind("index,", 0) != 0) throw std::invalid_argument(At(file, number) + "no column header after the manifest");
  table.header = line;
  const bool complete_last = !text.empty() && text.back() == '\n';
  while (std::getline(in, line)) {
    ++number;
    if (journal && in.eof() && !complete_last) break;  // cut off mid-write
    if (line.empty()) continue;
    const int index = LineIndex(line);
    if (index < 0) throw std::invalid_argument(At(file, number) + "not a sweep row");
    if (!table.lines.emplace(index, line).second) {
      throw std::invalid_argument(At(file, number) + "point " + std::to_string(index) + " appears twice");
    }
  }
  return table;
}

std::string MergeSweepCsv(const std::vector<std::pair<std::string, std::string>>& files_and_texts) {
  if (files_and_texts.empty()) throw std::invalid_argument("sweep-merge: no input files");
  std::vector<SweepTableText> tables;
  for (const auto& [file, text] : files_and_texts) tables.push_back(ReadSweepTable(text, file));
  const SweepManifest& first = tables.front().manifest;
  const std::string& first_file = files_and_texts.front().first;
  std::vector<const std::string*> by_shard(static_cast<std::size_t>(first.shard.count), nullptr);
  SweepTableText merged;
  merged.manifest = first;
  merged.manifest.shard = Shard{};
  merged.header = tables.front().header;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const SweepTableText& t = tables[i];
    const std::string& file = files_and_texts[i].first;
    const std::string difference = t.manifest.Difference(first);
    if (!difference.empty()) {
      throw std::invalid_argument(file + ": a different sweep from " + first_file + " (" + difference + ")");
    }
    if (t.header != merged.header) throw std::invalid_argument(file + ": column header differs from " + first_file + "'s");
    if (t.manifest.shard.count != first.shard.count) {
      throw std::invalid_argument(file + ": shard " + ShardText(t.manifest.shard) + " of a " +
                                  std::to_string(t.manifest.shard.count) + "-way split, but " + first_file +
                                  " is shard " + ShardText(first.shard));
    }
    const std::string*& owner = by_shard[static_cast<std::size_t>(t.manifest.shard.index)];
    if (owner != nullptr) {
      throw std::invalid_argument(file + ": shard " + ShardText(t.manifest.shard) + " given twice (also " + *owner + ")");
    }
    owner = &file;
    if (t.manifest.table == SweepTable::kPlans) {
      const std::vector<int> missing = MissingPoints(t);
      if (!missing.empty()) {
        throw std::invalid_argument(file + ": shard " + ShardText(t.manifest.shard) + " is incomplete: " +
                                    std::to_string(missing.size()) + " of its points missing (first: point " +
                                    std::to_string(missing.front()) + "); finish it with sweep --resume");
      }
    }
    for (const auto& [index, line] : t.lines) {
      if (!t.manifest.shard.Holds(index)) {
        throw std::invalid_argument(file + ": point " + std::to_string(index) + " is not shard " +
                                    ShardText(t.manifest.shard) + "'s");
      }
      merged.lines.emplace(index, line);
    }
  }
  std::string missing;
  for (std::size_t s = 0; s < by_shard.size(); ++s) {
    if (by_shard[s] == nullptr) missing += (missing.empty() ? "" : ", ") + ShardText(Shard{static_cast<int>(s), first.shard.count});
  }
  if (!missing.empty()) {
    throw std::invalid_argument("sweep-merge: shard " + missing + " missing (" + first_file + " is shard " +
                                ShardText(first.shard) + ")");
  }
  return merged.ToCsv();
}

}  // namespace stairplan
