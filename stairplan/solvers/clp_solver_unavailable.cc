// ClpSolver when stairplan is built without CLP (CMake did not find pkg-config's `clp`): every
// solve reports kInvalidInput through Supports(), and MakeSolver refuses the name.
#include "stairplan/solvers/clp_solver.h"

namespace stairplan::optim {

struct ClpSolver::Model {};

ClpSolver::ClpSolver() = default;
ClpSolver::ClpSolver(const ClpSettings& settings) : settings_(settings) { settings_.Validate(); }
ClpSolver::~ClpSolver() = default;

bool ClpSolver::IsAvailable() { return false; }

void ClpSolver::ResetWarmStart() {}

void ClpSolver::DoSolve(const Program&, SolveResult* result) { result->status = SolveStatus::kInvalidInput; }

}  // namespace stairplan::optim
