// Names of solve outcomes.
#include "stairplan/optim/solve_result.h"

namespace stairplan::optim {

std::string_view ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSolved: return "solved";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kUnbounded: return "unbounded";
    case SolveStatus::kIterationLimit: return "iteration_limit";
    case SolveStatus::kTimeLimit: return "time_limit";
    case SolveStatus::kNumericalError: return "numerical_error";
    case SolveStatus::kInvalidInput: return "invalid_input";
  }
  return "unknown";
}

}  // namespace stairplan::optim
