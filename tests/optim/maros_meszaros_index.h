// The index of the Maros-Meszaros set in ../shared/data/qp/maros_meszaros (INDEX.tsv: name, n,
// rows, published optimum, a note), for the conformance tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace stairplan::testing {

/// One problem of the set and its published optimum.
struct MarosMeszarosEntry {
  std::string name;
  double optimum = 0.0;
};

/// The problems INDEX.tsv in `dir` lists, in its order (empty when the file cannot be read).
inline std::vector<MarosMeszarosEntry> ReadMarosMeszarosIndex(const std::string& dir) {
  std::vector<MarosMeszarosEntry> entries;
  std::ifstream index(dir + "/INDEX.tsv");
  std::string line;
  std::getline(index, line);  // header
  while (std::getline(index, line)) {
    std::istringstream s(line);
    MarosMeszarosEntry e;
    int n = 0, m = 0;
    s >> e.name >> n >> m >> e.optimum;
    if (!e.name.empty()) entries.push_back(e);
  }
  return entries;
}

}  // namespace stairplan::testing
