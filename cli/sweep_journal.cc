#include "cli/sweep_journal.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "cli/cli_common.h"

namespace stairplan::cli {

SweepJournal::SweepJournal(std::string path, SweepManifest manifest, std::string header, bool resume)
    : path_(std::move(path)) {
  table_.manifest = std::move(manifest);
  table_.header = std::move(header);
  if (!resume || !std::filesystem::exists(path_)) return;
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw BadInput(path_ + ": cannot open to resume");
  std::stringstream text;
  text << in.rdbuf();
  SweepTableText earlier;
  try {
    earlier = ReadSweepTable(text.str(), path_, true);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string(e.what()) + " (cannot resume)");
  }
  std::string difference = earlier.manifest.Difference(table_.manifest);
  if (difference.empty() && earlier.manifest.shard.index != table_.manifest.shard.index) difference = "shard";
  if (difference.empty() && earlier.manifest.shard.count != table_.manifest.shard.count) difference = "shard";
  if (difference.empty() && earlier.header != table_.header) difference = "columns (--times)";
  if (!difference.empty()) {
    throw BadInput(path_ + ": --resume: the file holds a different sweep (" + difference + "); use the same flags or another --csv");
  }
  table_.lines = std::move(earlier.lines);
}

void SweepJournal::RetainOnly(const std::map<int, std::string>& done) {
  for (auto it = table_.lines.begin(); it != table_.lines.end();) {
    it = done.count(it->first) != 0 ? std::next(it) : table_.lines.erase(it);
  }
}

void SweepJournal::Open() {
  WriteFileAtomically(path_, table_.ToCsv());
  out_.open(path_, std::ios::binary | std::ios::app);
  if (!out_) throw BadInput(path_ + ": cannot open for appending");
}

void SweepJournal::Append(int index, const std::string& line) {
  table_.lines[index] = line;
  out_ << line << '\n';
  out_.flush();
  if (!out_) throw std::runtime_error(path_ + ": write failed");
}

std::string SweepJournal::Finish() {
  out_.close();
  const std::string csv = table_.ToCsv();
  WriteFileAtomically(path_, csv);
  return csv;
}

}  // namespace stairplan::cli
