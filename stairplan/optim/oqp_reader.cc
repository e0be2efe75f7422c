// The qpOASES sequence reader: whitespace-separated matrices, checked against dims.oqp.
#include "stairplan/optim/oqp_reader.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace stairplan::optim {
namespace {

// Reads a rows x cols matrix, one row per line; errors name the file and line.
Eigen::MatrixXd ReadMatrix(const std::string& path, int rows, int cols) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open the file");
  Eigen::MatrixXd M(rows, cols);
  std::string line;
  int r = 0, line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream s(line);
    std::string token;
    std::vector<double> values;
    while (s >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        throw std::invalid_argument(path + ":" + std::to_string(line_number) + ": '" + token + "' is not a number");
      }
      values.push_back(v);
    }
    if (values.empty()) continue;
    if (r >= rows) throw std::invalid_argument(path + ":" + std::to_string(line_number) + ": more than " + std::to_string(rows) + " rows");
    if (static_cast<int>(values.size()) != cols) {
      throw std::invalid_argument(path + ":" + std::to_string(line_number) + ": expected " + std::to_string(cols) +
                                  " values, found " + std::to_string(values.size()));
    }
    for (int c = 0; c < cols; ++c) M(r, c) = values[c];
    ++r;
  }
  if (r != rows) throw std::invalid_argument(path + ": expected " + std::to_string(rows) + " rows, found " + std::to_string(r));
  return M;
}

}  // namespace

OqpSequence ReadOqpSequence(const std::string& folder) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(folder)) throw std::invalid_argument(folder + ": not a folder");
  const auto file = [&](const char* name) { return (fs::path(folder) / name).string(); };
  const Eigen::MatrixXd dims = ReadMatrix(file("dims.oqp"), 4, 1);
  OqpSequence s;
  s.name = fs::path(folder).filename().string();
  if (s.name.empty()) s.name = fs::path(folder).parent_path().filename().string();
  // Checked before the casts (a double outside int's range is undefined behaviour) and before
  // any matrix is sized (a huge size would be a bad_alloc, not an error naming the file).
  for (int i = 0; i < 3; ++i) {
    if (!(dims(i) >= 0.0 && dims(i) <= 1e5) || dims(i) != static_cast<double>(static_cast<long>(dims(i)))) {
      throw std::invalid_argument(file("dims.oqp") + ": sizes must be whole numbers from 0 to 100000");
    }
  }
  if (dims(0) * dims(1) > 1e8 || dims(1) * dims(1) > 1e8 || dims(2) * dims(1) > 1e8 || dims(0) * dims(2) > 1e8) {
    throw std::invalid_argument(file("dims.oqp") + ": the matrices would hold more than 1e8 values");
  }
  s.num_qps = static_cast<int>(dims(0));
  s.num_variables = static_cast<int>(dims(1));
  s.num_constraints = static_cast<int>(dims(2));
  if (s.num_qps <= 0 || s.num_variables <= 0 || s.num_constraints < 0) {
    throw std::invalid_argument(file("dims.oqp") + ": sizes must be positive");
  }
  const int k = s.num_qps, n = s.num_variables, m = s.num_constraints;
  s.H = ReadMatrix(file("H.oqp"), n, n);
  s.A = m > 0 ? ReadMatrix(file("A.oqp"), m, n) : Eigen::MatrixXd(0, n);
  s.g = ReadMatrix(file("g.oqp"), k, n);
  s.lb = ReadMatrix(file("lb.oqp"), k, n);
  s.ub = ReadMatrix(file("ub.oqp"), k, n);
  s.lbA = m > 0 ? ReadMatrix(file("lbA.oqp"), k, m) : Eigen::MatrixXd(k, 0);
  s.ubA = m > 0 ? ReadMatrix(file("ubA.oqp"), k, m) : Eigen::MatrixXd(k, 0);
  s.x_opt = ReadMatrix(file("x_opt.oqp"), k, n);
  s.obj_opt = ReadMatrix(file("obj_opt.oqp"), k, 1).col(0);
  return s;
}

Program OqpSequence::MakeProgram() const {
  Program p;
  p.ResizeDense(num_variables, num_constraints);
  p.MutableHessian() = H;
  p.MutableConstraintMatrix() = A;
  Apply(0, &p);
  return p;
}

void OqpSequence::Apply(int k, Program* p) const {
  if (k < 0 || k >= num_qps) throw std::invalid_argument("OqpSequence::Apply: problem " + std::to_string(k) + " out of range");
  p->MutableLinearCost() = g.row(k).transpose();
  for (int j = 0; j < num_variables; ++j) {
    p->MutableVariableLower()[j] = NormalizeBound(lb(k, j));
    p->MutableVariableUpper()[j] = NormalizeBound(ub(k, j));
  }
  for (int i = 0; i < num_constraints; ++i) {
    p->MutableRowLower()[i] = NormalizeBound(lbA(k, i));
    p->MutableRowUpper()[i] = NormalizeBound(ubA(k, i));
  }
}

}  // namespace stairplan::optim
