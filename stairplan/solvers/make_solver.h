// Solvers by name or by program: every back-end, ours and the third-party ones (Ipopt, NLopt, CLP).
// In the solvers target, not the optimisation core, so that a program using only our QP solvers
// links none of those libraries.
#pragma once

#include <memory>
#include <string_view>

#include "stairplan/optim/program.h"
#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// The automatic choice: quadratic programs to ActiveSetQpSolver, the others to IpoptSolver.
std::unique_ptr<Solver> MakeSolver(const Program& program);

/// Solver by name ("active-set", "banded-ipm", "ipopt", "nlopt", "clp", "clp-barrier"); throws
/// std::invalid_argument naming it otherwise, or naming the missing package for CLP in a build without it.
std::unique_ptr<Solver> MakeSolver(std::string_view name);
/// The same with every solve limited to `time_limit_s` of wall time: a reference solver that
/// cycles (CLP's primal simplex can) then returns kTimeLimit instead of running on.
std::unique_ptr<Solver> MakeSolver(std::string_view name, double time_limit_s);

}  // namespace stairplan::optim
