// A body-planner-shaped QP for tests and benchmarks: the size and structure the per-cycle body
// planner solves (height, pitch and weight shift per knot; banded rows), with a deterministic
// per-cycle update of bounds and linear terms. Not a planner: the numbers are only plausible.
#pragma once

#include "stairplan/optim/program.h"

namespace stairplan::optim {

/// The program and the handles a cycle update needs.
struct BodyQpExample {
  Program program;  ///< the QP
  ///@{
  VariableBlock height, pitch, shift;  ///< one value per knot each
  ///@}
  ConstraintRows hip_heights;          ///< front and rear hip heights within kinematic bands
  ConstraintRows rates;                ///< height and pitch rate limits between knots
  int knots = 0;  ///< knots over the horizon
};

/// 40 knots by default: 3 variables per knot, 4 banded rows per knot.
BodyQpExample MakeBodyQpExample(int knots = 40);

/// Moves the example to planning cycle `cycle`: new reference heights (linear cost), new hip
/// height bands and variable bounds, as the robot advances along the stairs. Allocation-free.
void UpdateBodyQpExample(int cycle, BodyQpExample* example);

}  // namespace stairplan::optim
