// Reading QPs in the QPS format of the Maros-Meszaros set into a Program.
//
// objective = c'x + 0.5 x'Qx + constant, where QUADOBJ lists one triangle of Q (the off-diagonal
// entries are mirrored; QMATRIX lists both), and the constant is MINUS the RHS entry of the
// objective row. ROWS N/E/L/G, RANGES as in MPS, BOUNDS UP/LO/FX/FR/MI/PL/BV (default 0 <= x).
// Fields are whitespace separated. Numbers are parsed as written, "nan" included: Solve() then
// reports kInvalidInput.
#pragma once

#include <string>

#include "stairplan/optim/program.h"

namespace stairplan::optim {

/// A QP read from a QPS file, with the names it uses.
struct QpsProblem {
  std::string name;  ///< the NAME record
  Program program;  ///< one variable block "x"; rows in file order (the objective row excluded)
  std::vector<std::string> variable_names;  ///< in column order
  std::vector<std::string> row_names;  ///< in file order, the objective row excluded
};

/// Parses QPS text; `file` names the source in errors ("file:line: problem"), which are thrown as
/// std::invalid_argument.
QpsProblem ParseQps(const std::string& text, const std::string& file);

/// Reads a QPS file; throws std::invalid_argument naming the file (and line) on errors.
QpsProblem ReadQpsFile(const std::string& path);

}  // namespace stairplan::optim
