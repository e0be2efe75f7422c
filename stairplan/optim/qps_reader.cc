// The QPS reader: a line-by-line section parser with errors naming the file and line.
#include "stairplan/optim/qps_reader.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace stairplan::optim {
namespace {

enum class Section { kNone, kName, kRows, kColumns, kRhs, kRanges, kBounds, kQuadratic, kEnd };

struct Triplet {
  int i, j;
  double v;
};

class QpsParser {
 public:
  explicit QpsParser(std::string file) : file_(std::move(file)) {}

  QpsProblem Parse(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    Section section = Section::kNone;
    bool full_matrix = false;
    while (std::getline(in, line)) {
      ++line_number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty() || line[0] == '*') continue;
      std::vector<std::string> t = Split(line);
      if (t.empty()) continue;
      if (line[0] != ' ' && line[0] != '\t') {
        section = SectionOf(t[0]);
        if (section == Section::kName) name_ = t.size() > 1 ? t[1] : "";
        if (t[0] == "QMATRIX") full_matrix = true;
        if (section == Section::kEnd) break;
        continue;
      }
      switch (section) {
        case Section::kRows: Row(t); break;
        case Section::kColumns: Column(t); break;
        case Section::kRhs: Rhs(t); break;
        case Section::kRanges: Range(t); break;
        case Section::kBounds: Bound(t); break;
        case Section::kQuadratic: Quadratic(t, full_matrix); break;
        default: Fail("data outside a section");
      }
    }
    if (section != Section::kEnd) {
      line_number_ = 0;
      Fail("missing ENDATA");
    }
    if (objective_row_.empty()) Fail("no objective (N) row");
    return Build();
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const {
    if (line_number_ > 0) throw std::invalid_argument(file_ + ":" + std::to_string(line_number_) + ": " + problem);
    throw std::invalid_argument(file_ + ": " + problem);
  }

  static std::vector<std::string> Split(const std::string& line) {
    std::vector<std::string> tokens;
    std::istringstream s(line);
    std::string token;
    while (s >> token) tokens.push_back(token);
    return tokens;
  }

  Section SectionOf(const std::string& word) const {
    if (word == "NAME") return Section::kName;
    if (word == "ROWS") return Section::kRows;
    if (word == "COLUMNS") return Section::kColumns;
    if (word == "RHS") return Section::kRhs;
    if (word == "RANGES") return Section::kRanges;
    if (word == "BOUNDS") return Section::kBounds;
    if (word == "QUADOBJ" || word == "QSECTION" || word == "QMATRIX") return Section::kQuadratic;
    if (word == "ENDATA") return Section::kEnd;
    if (word == "OBJSENSE") Fail("OBJSENSE is not supported");
    Fail("unknown section '" + word + "'");
  }

  double Number(const std::string& token) const {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') Fail("'" + token + "' is not a number");
    return v;
  }

  int RowIndex(const std::string& name) const {
    const auto it = rows_.find(name);
    if (it == rows_.end()) Fail("unknown row '" + name + "'");
    return it->second;
  }

  int ColumnIndex(const std::string& name) const {
    const auto it = columns_.find(name);
    if (it == columns_.end()) Fail("unknown column '" + name + "'");
    return it->second;
  }

  void Row(const std::vector<std::string>& t) {
    if (t.size() != 2) Fail("a ROWS line needs a type and a name");
    const std::string& type = t[0];
    if (type == "N") {
      if (objective_row_.empty()) objective_row_ = t[1];  // further N rows are free rows: ignored
      else free_rows_.emplace(t[1], 0);
      return;
    }
    if (type != "E" && type != "L" && type != "G") Fail("unknown row type '" + type + "'");
    if (rows_.count(t[1])) Fail("duplicate row '" + t[1] + "'");
    rows_.emplace(t[1], static_cast<int>(row_names_.size()));
    row_names_.push_back(t[1]);
    row_types_.push_back(type[0]);
    rhs_.push_back(0.0);
    range_.push_back(0.0);
    has_range_.push_back(false);
  }

  void Column(const std::vector<std::string>& t) {
    if (t.size() >= 2 && t[1] == "'MARKER'") Fail("integer markers are not supported");
    if (t.size() != 3 && t.size() != 5) Fail("a COLUMNS line needs a column and one or two (row, value) pairs");
    int col;
    const auto it = columns_.find(t[0]);
    if (it == columns_.end()) {
      col = static_cast<int>(column_names_.size());
      columns_.emplace(t[0], col);
      column_names_.push_back(t[0]);
      cost_.push_back(0.0);
    } else {
      col = it->second;
    }
    for (std::size_t k = 1; k + 1 < t.size(); k += 2) {
      const double v = Number(t[k + 1]);
      if (t[k] == objective_row_) {
        cost_[col] += v;
      } else if (!free_rows_.count(t[k])) {
        entries_.push_back({RowIndex(t[k]), col, v});
      }
    }
  }

  // RHS and RANGES lines: [set name] (row value){1,2}.
  template <typename F>
  void Pairs(const std::vector<std::string>& t, const char* what, F&& apply) {
    const std::size_t first = t.size() % 2 == 1 ? 1 : 0;
    if (t.size() < 2 || t.size() > 5 || t.size() - first < 2) Fail(std::string("a ") + what + " line needs (row, value) pairs");
    for (std::size_t k = first; k + 1 < t.size(); k += 2) apply(t[k], Number(t[k + 1]));
  }

  void Rhs(const std::vector<std::string>& t) {
    Pairs(t, "RHS", [&](const std::string& row, double v) {
      if (row == objective_row_) {
        constant_ = -v;
      } else if (!free_rows_.count(row)) {
        rhs_[RowIndex(row)] = v;
      }
    });
  }

  void Range(const std::vector<std::string>& t) {
    Pairs(t, "RANGES", [&](const std::string& row, double v) {
      if (row == objective_row_ || free_rows_.count(row)) return;
      const int i = RowIndex(row);
      range_[i] = v;
      has_range_[i] = true;
    });
  }

  void Bound(const std::vector<std::string>& t) {
    if (t.empty()) Fail("empty BOUNDS line");
    const std::string& type = t[0];
    const bool valueless = type == "FR" || type == "MI" || type == "PL" || type == "BV";
    const std::size_t expected = valueless ? 3 : 4;
    if (t.size() != expected && t.size() != expected - 1) Fail("malformed " + type + " bound");
    const std::string& column = t.size() == expected ? t[2] : t[1];
    const int j = ColumnIndex(column);
    EnsureBounds();
    const double v = valueless ? 0.0 : Number(t.back());
    if (type == "UP" || type == "UI") {
      upper_[j] = v;
      if (v < 0 && lower_[j] == 0.0 && !lower_set_[j]) lower_[j] = -kInf;  // the MPS convention
    } else if (type == "LO" || type == "LI") {
      lower_[j] = v;
      lower_set_[j] = true;
    } else if (type == "FX") {
      lower_[j] = upper_[j] = v;
      lower_set_[j] = true;
    } else if (type == "FR") {
      lower_[j] = -kInf;
      upper_[j] = kInf;
    } else if (type == "MI") {
      lower_[j] = -kInf;
      lower_set_[j] = true;
    } else if (type == "PL") {
      upper_[j] = kInf;
    } else if (type == "BV") {
      lower_[j] = 0.0;
      upper_[j] = 1.0;
    } else {
      Fail("unknown bound type '" + type + "'");
    }
  }

  void Quadratic(const std::vector<std::string>& t, bool full_matrix) {
    if (t.size() != 3) Fail("a QUADOBJ line needs two columns and a value");
    const int i = ColumnIndex(t[0]), j = ColumnIndex(t[1]);
    const double v = Number(t[2]);
    quadratic_.push_back({i, j, v});
    if (i != j && !full_matrix) quadratic_.push_back({j, i, v});
  }

  void EnsureBounds() {
    const std::size_t n = column_names_.size();
    if (lower_.size() == n) return;
    lower_.resize(n, 0.0);
    upper_.resize(n, kInf);
    lower_set_.resize(n, false);
  }

  QpsProblem Build() {
    EnsureBounds();
    const int n = static_cast<int>(column_names_.size());
    const int m = static_cast<int>(row_names_.size());
    line_number_ = 0;
    if (n == 0) Fail("no columns");
    QpsProblem problem;
    problem.name = name_;
    Program& p = problem.program;
    p.ResizeDense(n, m);
    Eigen::MatrixXd& H = p.MutableHessian();
    for (const Triplet& e : quadratic_) H(e.i, e.j) += e.v;
    Eigen::MatrixXd& A = p.MutableConstraintMatrix();
    for (const Triplet& e : entries_) A(e.i, e.j) += e.v;
    for (int j = 0; j < n; ++j) p.MutableLinearCost()[j] = cost_[j];
    for (int i = 0; i < m; ++i) {
      const double b = rhs_[i], r = range_[i];
      double lo = b, hi = b;
      switch (row_types_[i]) {
        case 'E':
          if (has_range_[i]) (r > 0 ? hi : lo) += r;
          break;
        case 'L':
          lo = has_range_[i] ? b - std::abs(r) : -kInf;
          break;
        case 'G':
          hi = has_range_[i] ? b + std::abs(r) : kInf;
          break;
      }
      p.MutableRowLower()[i] = NormalizeBound(lo);
      p.MutableRowUpper()[i] = NormalizeBound(hi);
    }
    for (int j = 0; j < n; ++j) {
      p.MutableVariableLower()[j] = NormalizeBound(lower_[j]);
      p.MutableVariableUpper()[j] = NormalizeBound(upper_[j]);
      // Start inside the bounds: the nonlinear solvers need a sensible first point.
      const double lo = p.variable_lower()[j], hi = p.variable_upper()[j];
      p.MutableInitialGuess()[j] = std::isfinite(lo) ? lo : (std::isfinite(hi) ? std::min(hi, 0.0) : 0.0);
    }
    p.SetConstant(constant_);
    problem.variable_names = column_names_;
    problem.row_names = row_names_;
    return problem;
  }

  std::string file_;
  int line_number_ = 0;
  std::string name_;
  std::string objective_row_;
  std::unordered_map<std::string, int> rows_, columns_, free_rows_;
  std::vector<std::string> row_names_, column_names_;
  std::vector<char> row_types_;
  std::vector<double> rhs_, range_, cost_, lower_, upper_;
  std::vector<bool> has_range_, lower_set_;
  std::vector<Triplet> entries_, quadratic_;
  double constant_ = 0.0;
};

}  // namespace

QpsProblem ParseQps(const std::string& text, const std::string& file) { return QpsParser(file).Parse(text); }

QpsProblem ReadQpsFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open the file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseQps(buffer.str(), path);
}

}  // namespace stairplan::optim
