// How a solve starts, for benchmarks that compare like with like: a regime is never mixed with
// another in one comparison.
//
//   kCold              a fresh solver object and no guess (factorisations and setup included)
//   kWarmSequence      each problem of a sequence from the previous problem's solution and active
//                      set, the data changed in between (a control loop's next cycle); every
//                      solver is warm-started, Ipopt with its multipliers too (WarmStartFrom)
//   kIdenticalResolve  the same problem again on the same solver object, from its own last
//                      solution: a lower bound on any re-solve, never to be compared with the others
#pragma once

#include <string_view>

#include "stairplan/optim/solver.h"

namespace stairplan::optim {

/// How a benchmarked solve starts (see the file's top comment): never mixed in one comparison.
enum class SolveRegime { kCold, kWarmSequence, kIdenticalResolve };

/// "cold", "warm-sequence", "identical-resolve" (stable names for CSV and the CLI).
std::string_view ToString(SolveRegime regime);

/// Prepares `solver`'s next solve of `program` to start from `previous` (a solution of the
/// program before its data changed), the same way for every back-end: the program's initial
/// guess becomes previous.x (where Ipopt and NLopt start); Ipopt also starts from previous's
/// multipliers (warm_start_init_point) with the warm-start pushes and the initial barrier
/// parameter small, so that it stays near the point instead of moving back into the interior;
/// the active-set solver and CLP keep their own state (the last active set and factorisation,
/// the last basis). An unsolved `previous` of the wrong size leaves the solver cold.
void WarmStartFrom(const SolveResult& previous, Solver* solver, Program* program);

}  // namespace stairplan::optim
