// A sweep across the ranks of an MPI job (`mpirun -np N stairplan sweep ...`): rank 0 hands out
// points one at a time as ranks ask for work, so the slow points at steep corners never idle the
// others, computes points itself on its own threads, and receives every result. Whether MPI is
// there is decided in CMake: sweep_cluster_mpi.cc with Open MPI, sweep_cluster_none.cc without.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace stairplan::cli {

class SweepCluster {
 public:
  virtual ~SweepCluster() = default;

  /// This process's rank (0 coordinates and writes) and the number of ranks.
  virtual int Rank() const = 0;
  virtual int Size() const = 0;

  /// Computes each point index of `todo` once on some rank: `compute(index)` runs on every rank
  /// (on rank 0 on `local_threads` threads) and its result reaches `deliver` on rank 0, serialised.
  /// On ranks other than 0, `todo` and `deliver` are unused and it returns when rank 0 is done.
  /// Called once per sweep; every rank must call it the same number of times.
  virtual void Run(const std::vector<int>& todo, const std::function<std::string(int index)>& compute,
                   const std::function<void(const std::string& result)>& deliver, int local_threads) = 0;

  /// Collective, before each Run: whether every rank got `ready` (parsed its flags, loaded the
  /// robot; rank 0 also opened its files). When one did not, no rank may call Run: all stop.
  virtual bool AllReady(bool ready) = 0;
};

/// The MPI job this process is a rank of, or nullptr: a build without MPI, or a process not
/// started by mpirun. MPI is finalised when the returned object is destroyed.
std::unique_ptr<SweepCluster> JoinSweepCluster();

}  // namespace stairplan::cli
