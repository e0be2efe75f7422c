// Conformance over the 34 small Maros-Meszaros QPs (../shared/data/qp/maros_meszaros): the
// active-set solver must reach the published optimum (1e-6 relative; 1e-6 absolute where the
// optimum is 0) on at least 30 of them. Prints a table with Ipopt's results beside.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/optim/qp_residuals.h"
#include "stairplan/optim/qps_reader.h"
#include "maros_meszaros_index.h"
#include "test_paths.h"

using namespace stairplan::optim;
using stairplan::testing::MarosMeszarosEntry;
using stairplan::testing::ReadMarosMeszarosIndex;
using stairplan::testing::SharedPath;

namespace {

bool OptimumIsZero(const std::string& name) {
  // HS268/S268: the true optimum is 0 (the published 5.7e-7 is inexact); HS51 and TAME are 0.
  return name == "HS268" || name == "S268" || name == "HS51" || name == "TAME";
}

double Error(const std::string& name, double objective, double optimum) {
  if (OptimumIsZero(name)) return std::abs(objective);
  return std::abs(objective - optimum) / std::abs(optimum);
}

}  // namespace

TEST_CASE("Maros-Meszaros: the active-set solver reaches the published optima", "[conformance]") {
  const std::string dir = SharedPath("data/qp/maros_meszaros");
  if (dir.empty()) {
    WARN("Maros-Meszaros conformance skipped: ../shared not found");
    return;
  }
  const std::vector<MarosMeszarosEntry> entries = ReadMarosMeszarosIndex(dir);
  REQUIRE(entries.size() == 34);
  int passed = 0;
  std::vector<std::string> failures;
  std::printf("%-10s %-16s %-18s %-9s %-7s %-16s %-18s\n", "problem", "active-set", "objective", "error", "iters",
              "ipopt", "objective");
  for (const MarosMeszarosEntry& e : entries) {
    const QpsProblem q = ReadQpsFile(dir + "/" + e.name + ".SIF");
    ActiveSetQpSolver ours;
    const SolveResult r = ours.Solve(q.program);
    const double error = Error(e.name, r.objective, e.optimum);
    const bool ok = r.status == SolveStatus::kSolved && error <= 1e-6;
    IpoptSolver ipopt;
    const SolveResult ri = ipopt.Solve(q.program);
    std::printf("%-10s %-16s %-18.10e %-9.1e %-7d %-16s %-18.10e%s\n", e.name.c_str(),
                std::string(ToString(r.status)).c_str(), r.objective, error, r.info.iterations,
                std::string(ToString(ri.status)).c_str(), ri.objective, ok ? "" : "  FAILED");
    if (ok) {
      ++passed;
      // A solved answer is feasible in the problem's own terms.
      CHECK(q.program.MaxViolation(r.x) <= 1e-6 * (1.0 + r.x.lpNorm<Eigen::Infinity>()));
    } else {
      failures.push_back(e.name);
    }
  }
  std::string failed;
  for (const auto& f : failures) failed += f + " ";
  std::printf("Maros-Meszaros: %d of %zu within 1e-6; failures: %s\n", passed, entries.size(),
              failed.empty() ? "none" : failed.c_str());
  INFO("failures: " << failed);
  CHECK(passed >= 30);
}

// The residuals qpbenchmark judges by are absolute: on DUALC1 and DUALC2 (9 and 7 variables, 215
// and 229 rows, |g| ~ 1e6) the Givens-updated factors leave a dual residual of 2e-9 to 3e-8, and
// the refinement on the final active set brings it below 1e-9, where CLP gets too.
TEST_CASE("Maros-Meszaros: refinement brings DUALC1 and DUALC2 to 1e-9 residuals", "[conformance]") {
  const std::string dir = SharedPath("data/qp/maros_meszaros");
  if (dir.empty()) {
    WARN("Maros-Meszaros refinement skipped: ../shared not found");
    return;
  }
  for (const char* name : {"DUALC1", "DUALC2"}) {
    const QpsProblem q = ReadQpsFile(dir + "/" + name + ".SIF");
    ActiveSetQpSettings settings;
    settings.refinement_steps = ActiveSetQpSettings::kHighAccuracyRefinementSteps;
    ActiveSetQpSolver refined(settings);
    const SolveResult r = refined.Solve(q.program);
    INFO(name);
    REQUIRE(r.status == SolveStatus::kSolved);
    const QpResiduals residuals = ComputeQpResiduals(q.program, r);
    CHECK(residuals.primal < 1e-9);
    CHECK(residuals.dual < 1e-9);
    CHECK(residuals.gap < 1e-9);
    // Refinement moves the answer within rounding: the unrefined solve's objective.
    ActiveSetQpSolver plain;
    CHECK(std::abs(plain.Solve(q.program).objective - r.objective) <= 1e-9 * std::abs(r.objective));
  }
}
