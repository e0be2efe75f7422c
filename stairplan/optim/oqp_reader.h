// Reading Online QP Benchmark sequences in the plain-text qpOASES format (a folder of *.oqp).
//
// Problem k: min 0.5 x'Hx + g_k'x s.t. lb_k <= x <= ub_k, lbA_k <= A x <= ubA_k, with H and A
// shared by the sequence; x_opt and obj_opt hold the reference solutions.
#pragma once

#include <string>

#include <Eigen/Core>

#include "stairplan/optim/program.h"

namespace stairplan::optim {

/// One sequence of QPs sharing H and A. Per-problem data is stored one problem per row.
struct OqpSequence {
  std::string name;  ///< the sequence's folder name
  ///@{
  int num_qps = 0, num_variables = 0, num_constraints = 0;  ///< sizes: problems, variables, constraint rows
  ///@}
  ///@{
  Eigen::MatrixXd H, A;  ///< the shared Hessian and constraint matrix
  ///@}
  ///@{
  Eigen::MatrixXd g, lb, ub, lbA, ubA;  ///< num_qps rows
  ///@}
  Eigen::MatrixXd x_opt;                ///< num_qps rows
  Eigen::VectorXd obj_opt;  ///< the reference optimal objective per problem

  /// A program with H and A and problem 0's vectors.
  Program MakeProgram() const;
  /// Loads problem k's vectors into a program made by MakeProgram() (in place, no allocation).
  void Apply(int k, Program* program) const;
};

/// Reads dims.oqp, H, A, g, lb, ub, lbA, ubA, x_opt and obj_opt from `folder`; errors (thrown as
/// std::invalid_argument) name the file and line.
OqpSequence ReadOqpSequence(const std::string& folder);

}  // namespace stairplan::optim
