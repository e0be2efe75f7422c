// Counting heap allocations in a test program, to prove that per-cycle paths allocate nothing
// after warm-up. Add tests/alloc_counter.cc to the sources of the test program that uses it: it
// replaces the global operator new for that program.
#pragma once

#include <cstddef>

namespace stairplan::testing {

/// Allocations made by this thread since the program started.
std::size_t AllocationCount();

/// Counts the allocations made on this thread while it is alive.
class AllocationScope {
 public:
  AllocationScope() : start_(AllocationCount()) {}
  std::size_t count() const { return AllocationCount() - start_; }

 private:
  std::size_t start_;
};

}  // namespace stairplan::testing
