// What ClpSolver is with or without CLP: its settings' checks and its name.
#include <stdexcept>
#include <string>

#include "stairplan/solvers/clp_solver.h"

namespace stairplan::optim {

void ClpSettings::Validate() const {
  const auto fail = [](const std::string& field) {
    throw std::invalid_argument("ClpSettings::" + field + " is out of range");
  };
  if (!(primal_tolerance > 0 && primal_tolerance < 1)) fail("primal_tolerance");
  if (!(dual_tolerance > 0 && dual_tolerance < 1)) fail("dual_tolerance");
  if (max_iterations <= 0) fail("max_iterations");
  if (!(time_limit_s > 0)) fail("time_limit_s");
}

std::string_view ClpSolver::name() const {
  return settings_.algorithm == ClpAlgorithm::kBarrier ? "clp-barrier" : "clp";
}

}  // namespace stairplan::optim
