// The solver factory: a back-end by name, or the automatic choice for a program.
#include "stairplan/solvers/make_solver.h"

#include <stdexcept>
#include <string>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/banded_ipm_qp_solver.h"
#include "stairplan/solvers/clp_solver.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"

namespace stairplan::optim {

std::unique_ptr<Solver> MakeSolver(const Program& program) {
  if (program.IsQuadratic()) return std::make_unique<ActiveSetQpSolver>();
  return std::make_unique<IpoptSolver>();
}

std::unique_ptr<Solver> MakeSolver(std::string_view name) {
  if (name == "active-set") return std::make_unique<ActiveSetQpSolver>();
  if (name == "banded-ipm") return std::make_unique<BandedIpmQpSolver>();
  if (name == "ipopt") return std::make_unique<IpoptSolver>();
  if (name == "nlopt") return std::make_unique<NloptSolver>();
  if (name == "clp" || name == "clp-barrier") {
    if (!ClpSolver::IsAvailable()) {
      throw std::invalid_argument("solver '" + std::string(name) + "' needs CLP: install coinor-libclp-dev and rebuild");
    }
    ClpSettings settings;
    if (name == "clp-barrier") settings.algorithm = ClpAlgorithm::kBarrier;
    return std::make_unique<ClpSolver>(settings);
  }
  throw std::invalid_argument("unknown solver '" + std::string(name) +
                              "' (expected active-set, banded-ipm, ipopt, nlopt, clp or clp-barrier)");
}

std::unique_ptr<Solver> MakeSolver(std::string_view name, double time_limit_s) {
  if (!(time_limit_s > 0)) throw std::invalid_argument("time_limit_s: must be positive");
  std::unique_ptr<Solver> solver = MakeSolver(name);
  if (auto* s = dynamic_cast<ActiveSetQpSolver*>(solver.get())) s->settings().time_limit_s = time_limit_s;
  if (auto* s = dynamic_cast<BandedIpmQpSolver*>(solver.get())) s->settings().time_limit_s = time_limit_s;
  if (auto* s = dynamic_cast<IpoptSolver*>(solver.get())) s->settings().time_limit_s = time_limit_s;
  if (auto* s = dynamic_cast<NloptSolver*>(solver.get())) s->settings().time_limit_s = time_limit_s;
  if (auto* s = dynamic_cast<ClpSolver*>(solver.get())) s->settings().time_limit_s = time_limit_s;
  return solver;
}

}  // namespace stairplan::optim
