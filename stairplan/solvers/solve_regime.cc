// The regimes' names and the warm start every back-end gets in the warm-sequence regime.
#include "stairplan/solvers/solve_regime.h"

#include "stairplan/solvers/ipopt_solver.h"

namespace stairplan::optim {

std::string_view ToString(SolveRegime regime) {
  switch (regime) {
    case SolveRegime::kCold: return "cold";
    case SolveRegime::kWarmSequence: return "warm-sequence";
    case SolveRegime::kIdenticalResolve: return "identical-resolve";
  }
  return "unknown";
}

void WarmStartFrom(const SolveResult& previous, Solver* solver, Program* program) {
  const int n = program->num_variables();
  if (previous.x.size() != n || !previous.x.allFinite()) return;
  program->MutableInitialGuess() = previous.x;
  auto* ipopt = dynamic_cast<IpoptSolver*>(solver);
  if (ipopt == nullptr) return;
  if (previous.row_duals.size() != program->num_rows() || previous.bound_duals.size() != n ||
      previous.nonlinear_duals.size() != program->num_nonlinear_rows()) {
    ipopt->ClearDualGuess();
    return;
  }
  ipopt->SetDualGuess({previous.row_duals, previous.nonlinear_duals, previous.bound_duals});
  auto& options = ipopt->settings().numeric_options;
  options["mu_init"] = 1e-6;
  for (const char* push : {"warm_start_bound_push", "warm_start_bound_frac", "warm_start_slack_bound_push",
                           "warm_start_slack_bound_frac", "warm_start_mult_bound_push"}) {
    options[push] = 1e-6;
  }
}

}  // namespace stairplan::optim
