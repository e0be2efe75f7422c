// The Online QP Benchmark sequences diesel and crane (../shared/data/qp/online_qp): every QP
// matches its reference solution within 1e-6 (scaled inf-norm) when each is warm-started from the
// previous one, and warm starts take fewer iterations on average than cold starts.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/optim/oqp_reader.h"
#include "test_paths.h"

using namespace stairplan::optim;
using stairplan::testing::SharedPath;

namespace {

struct SequenceRun {
  int mismatches = 0;
  double worst_error = 0.0;
  double mean_iterations = 0.0;
};

SequenceRun Run(const OqpSequence& s, bool warm) {
  Program p = s.MakeProgram();
  ActiveSetQpSettings settings;
  settings.warm_start = warm;
  ActiveSetQpSolver solver(settings);
  SolveResult r;
  SequenceRun run;
  long iterations = 0;
  for (int k = 0; k < s.num_qps; ++k) {
    s.Apply(k, &p);
    solver.Solve(p, &r);
    const Eigen::VectorXd reference = s.x_opt.row(k).transpose();
    const double error = (r.x - reference).lpNorm<Eigen::Infinity>() / std::max(1.0, reference.lpNorm<Eigen::Infinity>());
    run.worst_error = std::max(run.worst_error, error);
    if (r.status != SolveStatus::kSolved || error > 1e-6) ++run.mismatches;
    iterations += r.info.iterations;
  }
  run.mean_iterations = static_cast<double>(iterations) / s.num_qps;
  return run;
}

void CheckSequence(const std::string& name) {
  const std::string dir = SharedPath("data/qp/online_qp/" + name);
  if (dir.empty()) {
    WARN("online QP " << name << " skipped: ../shared not found");
    return;
  }
  const OqpSequence s = ReadOqpSequence(dir);
  const SequenceRun warm = Run(s, true);
  const SequenceRun cold = Run(s, false);
  std::printf("%s: %d QPs, warm: %d mismatches, worst error %.1e, %.2f iterations per QP; cold: %.2f\n",
              name.c_str(), s.num_qps, warm.mismatches, warm.worst_error, warm.mean_iterations, cold.mean_iterations);
  CHECK(warm.mismatches == 0);
  CHECK(cold.mismatches == 0);
  CHECK(warm.mean_iterations < cold.mean_iterations);
}

}  // namespace

TEST_CASE("online QP diesel: warm-started solves match the reference", "[conformance]") { CheckSequence("diesel"); }

TEST_CASE("online QP crane: warm-started solves match the reference", "[conformance]") { CheckSequence("crane"); }
