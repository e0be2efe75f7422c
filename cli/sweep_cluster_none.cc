// A build without MPI: sweeps run in one process (threads and shards).
#include "cli/sweep_cluster.h"

namespace stairplan::cli {

std::unique_ptr<SweepCluster> JoinSweepCluster() { return nullptr; }

}  // namespace stairplan::cli
