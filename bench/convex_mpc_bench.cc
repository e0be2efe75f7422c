// The executor's convex MPC QP (stairplan/simulation/convex_mpc.h, 10 knots of 40 ms, 120 forces)
// along a trot at 100 Hz: each cycle the body has moved 3.5 mm, its state is off the reference by
// a few millimetres and milliradians, and every 0.4 s a diagonal pair lifts or lands. Our
// active-set solver and Ipopt solve the same sequence, cold (a fresh solver each cycle) and warm
// (each cycle from the last one's solution; Ipopt with its multipliers too). Times are process
// CPU time per solve, p50 and p99; ratios only within a regime.
//
//   ./convex_mpc_bench                       (STAIRPLAN_BENCH_SMOKE=1: a few cycles, for ctest)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "stairplan/simulation/convex_mpc.h"
#include "stairplan/solvers/make_solver.h"
#include "stairplan/solvers/qp_benchmark.h"

using namespace stairplan;
using namespace stairplan::optim;

namespace {

bool Smoke() { return std::getenv("STAIRPLAN_BENCH_SMOKE") != nullptr; }

constexpr double kMass = 30.0, kSpeed = 0.35, kHeight = 0.4;  // [kg], [m/s], [m]
constexpr double kSwing = 0.25, kSlot = 0.4, kStride = 2.0 * kSlot * kSpeed;  // [s], [s], [m]

// Leg i (LF, RF, LH, RH) at time t: whether it stands, and its foothold. LF and RH swing in the
// first 0.25 s of every 0.8 s, RF and LH in the first 0.25 s of the second half.
bool FootAt(int i, double t, Eigen::Vector3d& foot) {
  const double x0 = i < 2 ? 0.3 : -0.3, y = i % 2 == 0 ? 0.18 : -0.18;
  const double offset = (i == 0 || i == 3) ? 0.0 : kSlot;
  const double since = t - offset;
  const double cycles = std::floor(since / (2.0 * kSlot));
  const double in_cycle = since - cycles * 2.0 * kSlot;
  const bool swinging = since >= 0.0 && in_cycle < kSwing;
  const double landed = since < 0.0 ? 0.0 : cycles + (swinging ? 0.0 : 1.0);
  foot = Eigen::Vector3d(x0 + landed * kStride, y, 0.0);
  return !swinging;
}

// The problem of cycle k (10 ms apart): the knots along the trot and a state a little off them.
void FillCycle(int k, ConvexMpc& mpc, std::vector<MpcKnot>& knots) {
  const double now = 0.01 * k, dt = mpc.settings().knot_dt;
  for (std::size_t j = 0; j < knots.size(); ++j) {
    const double t = now + dt * static_cast<double>(j);
    MpcKnot& knot = knots[j];
    knot.position_W = Eigen::Vector3d(kSpeed * t, 0.0, kHeight);
    knot.velocity_W = Eigen::Vector3d(kSpeed, 0.0, 0.0);
    knot.inertia_W = Eigen::Vector3d(0.3, 0.8, 0.9).asDiagonal();
    for (int i = 0; i < 4; ++i) {
      const bool stands = FootAt(i, t, knot.feet_W[static_cast<std::size_t>(i)]);
      knot.max_normal[static_cast<std::size_t>(i)] = stands ? 3.0 * kMass * 9.81 : 0.0;
    }
  }
  MpcState state;
  state.position_W = knots[0].position_W + Eigen::Vector3d(0.004 * std::sin(7.0 * now), 0.003 * std::cos(5.0 * now), 0.002 * std::sin(3.0 * now));
  state.velocity_W = knots[0].velocity_W + Eigen::Vector3d(0.02 * std::cos(7.0 * now), 0.03 * std::sin(5.0 * now), 0.0);
  state.attitude_error_W = Eigen::Vector3d(0.01 * std::sin(11.0 * now), 0.008 * std::cos(9.0 * now), 0.0);
  state.angular_velocity_W = Eigen::Vector3d(0.1 * std::cos(11.0 * now), 0.07 * std::sin(9.0 * now), 0.0);
  mpc.Fill(state, knots.data(), MpcMotors{});
}

SolverFactory Factory(const std::string& name) { return BenchmarkSolverFactory(name, Smoke() ? 1.0 : 10.0); }

struct Row {
  double p50_us = 0, p99_us = 0, iterations = 0;
  int qps = 0, solved = 0;
};
std::map<std::string, std::map<std::string, Row>>& Table() {
  static std::map<std::string, std::map<std::string, Row>> table;
  return table;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

void MpcSequence(benchmark::State& state, const std::string& solver, SolveRegime regime) {
  const int cycles = Smoke() ? 8 : 400;
  std::vector<QpSample> samples;
  for (auto _ : state) {
    ConvexMpc mpc(kMass);
    std::vector<MpcKnot> knots(static_cast<std::size_t>(mpc.settings().knots));
    FillCycle(0, mpc, knots);
    samples = MeasureSequence(Factory(solver), regime, mpc.mutable_program(), cycles,
                              [&](int k, Program*) { FillCycle(k, mpc, knots); });
  }
  std::vector<double> times;
  Row row;
  for (const QpSample& s : samples) {
    times.push_back(s.cpu_us);
    row.iterations += s.iterations;
    row.solved += s.SolvedWithin(kMidAccuracy) ? 1 : 0;
  }
  row.qps = static_cast<int>(samples.size());
  row.iterations /= std::max(1, row.qps);
  row.p50_us = Percentile(times, 0.5);
  row.p99_us = Percentile(times, 0.99);
  Table()[std::string(ToString(regime))][solver] = row;
  state.counters["p50_us"] = row.p50_us;
  state.counters["p99_us"] = row.p99_us;
  state.counters["it_per_qp"] = row.iterations;
  state.counters["solved_1e-6"] = row.solved;
}

void PrintTable() {
  std::printf("\nConvex MPC QP along a trot, CPU time per solve (ratios within a regime, against active-set);\nmachine: %s\n",
              DescribeMachine().c_str());
  for (const auto& [regime, rows] : Table()) {
    std::printf("%s\n", regime.c_str());
    const auto base = rows.find("active-set");
    for (const auto& [solver, r] : rows) {
      std::printf("  %-11s p50 %9.1f us  p99 %9.1f us  %6.1f it/QP  solved@1e-6 %4d/%-4d", solver.c_str(), r.p50_us,
                  r.p99_us, r.iterations, r.solved, r.qps);
      if (base != rows.end() && solver != "active-set") std::printf("  p50 ratio %.3g", r.p50_us / base->second.p50_us);
      std::printf("\n");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const std::string solver : {"active-set", "ipopt"}) {
    for (const SolveRegime regime : {SolveRegime::kCold, SolveRegime::kWarmSequence}) {
      benchmark::RegisterBenchmark(("ConvexMpc/" + std::string(ToString(regime)) + "/" + solver).c_str(), MpcSequence,
                                   solver, regime)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  PrintTable();
  return 0;
}
