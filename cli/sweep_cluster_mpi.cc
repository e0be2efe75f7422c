// The sweep cluster over Open MPI. Only the main thread calls MPI (MPI_THREAD_FUNNELED); rank 0's
// worker threads share its queue of points under a mutex. Waiting is a probe-and-sleep loop, not a
// blocking receive: Open MPI's blocking calls spin, and on an oversubscribed machine a spinning
// coordinator would take a core from the ranks that compute.
// Every call goes to the PMPI_ name: Debian's sequential MUMPS (under Ipopt) defines stub
// MPI_Init, MPI_Comm_rank and MPI_Finalize that come first in the symbol lookup, so MPI_Comm_rank
// would say rank 0 on every rank. The PMPI_ entry points are Open MPI's alone.
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "cli/sweep_cluster.h"

namespace stairplan::cli {
namespace {

constexpr int kResultTag = 1;  // worker -> rank 0: a result (empty: the first request for work)
constexpr int kWorkTag = 2;    // rank 0 -> worker: a point index, or kNoMoreWork
constexpr int kNoMoreWork = -1;

bool StartedByMpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

MPI_Status WaitFor(int source, int tag) {
  MPI_Status status;
  for (int flag = 0;;) {
    PMPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (flag != 0) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

std::string ReceiveText(const MPI_Status& probed) {
  int size = 0;
  PMPI_Get_count(&probed, MPI_CHAR, &size);
  std::string text(static_cast<std::size_t>(size), '\0');
  PMPI_Recv(text.data(), size, MPI_CHAR, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

void SendText(const std::string& text, int destination) {
  PMPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, destination, kResultTag, MPI_COMM_WORLD);
}

class MpiSweepCluster final : public SweepCluster {
 public:
  MpiSweepCluster() {
    int provided = 0;
    PMPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    PMPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (provided < MPI_THREAD_FUNNELED) {
      PMPI_Finalize();
      throw std::runtime_error("MPI: this library cannot run threads beside MPI (MPI_THREAD_FUNNELED)");
    }
  }
  ~MpiSweepCluster() override { PMPI_Finalize(); }
  MpiSweepCluster(const MpiSweepCluster&) = delete;
  MpiSweepCluster& operator=(const MpiSweepCluster&) = delete;

  int Rank() const override { return rank_; }
  int Size() const override { return size_; }

  bool AllReady(bool ready) override {
    int mine = ready ? 1 : 0, all = 0;
    PMPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
  }

  void Run(const std::vector<int>& todo, const std::function<std::string(int)>& compute,
           const std::function<void(const std::string&)>& deliver, int local_threads) override {
    if (rank_ != 0) {
      Work(compute);
      return;
    }
    try {
      Coordinate(todo, compute, deliver, local_threads);
    } catch (const std::exception&) {
      // The other ranks wait for work that will never come: end the whole job.
      PMPI_Abort(MPI_COMM_WORLD, 1);
    }
  }

 private:
  void Work(const std::function<std::string(int)>& compute) {
    std::string result;  // empty: the first request
    for (;;) {
      SendText(result, 0);
      WaitFor(0, kWorkTag);
      int index = kNoMoreWork;
      PMPI_Recv(&index, 1, MPI_INT, 0, kWorkTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (index == kNoMoreWork) return;
      result = compute(index);
    }
  }

  void Coordinate(const std::vector<int>& todo, const std::function<std::string(int)>& compute,
                  const std::function<void(const std::string&)>& deliver, int local_threads) {
    std::deque<int> queue(todo.begin(), todo.end());
    std::mutex queue_mutex, deliver_mutex;
    const auto next = [&] {
      const std::lock_guard<std::mutex> lock(queue_mutex);
      if (queue.empty()) return kNoMoreWork;
      const int index = queue.front();
      queue.pop_front();
      return index;
    };
    std::exception_ptr failure;
    const auto local = [&] {
      try {
        for (int index = next(); index != kNoMoreWork; index = next()) {
          const std::string result = compute(index);
          const std::lock_guard<std::mutex> lock(deliver_mutex);
          deliver(result);
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(deliver_mutex);
        failure = std::current_exception();
      }
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < std::max(1, local_threads); ++t) threads.emplace_back(local);
    for (int waiting = size_ - 1; waiting > 0;) {
      const MPI_Status status = WaitFor(MPI_ANY_SOURCE, kResultTag);
      const std::string result = ReceiveText(status);
      if (!result.empty()) {
        const std::lock_guard<std::mutex> lock(deliver_mutex);
        deliver(result);
      }
      const int index = next();
      PMPI_Send(&index, 1, MPI_INT, status.MPI_SOURCE, kWorkTag, MPI_COMM_WORLD);
      if (index == kNoMoreWork) --waiting;
    }
    for (std::thread& t : threads) t.join();
    if (failure) std::rethrow_exception(failure);
  }

  int rank_ = 0;
  int size_ = 1;
};

}  // namespace

std::unique_ptr<SweepCluster> JoinSweepCluster() {
  if (!StartedByMpirun()) return nullptr;
  return std::make_unique<MpiSweepCluster>();
}

}  // namespace stairplan::cli
