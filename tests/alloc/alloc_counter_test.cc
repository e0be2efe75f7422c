// The allocation counter itself must see allocations, or every zero-allocation test is void.
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "alloc_counter.h"

TEST_CASE("the allocation counter sees new and vector growth", "[alloc]") {
  stairplan::testing::AllocationScope scope;
  auto p = std::make_unique<int>(3);
  std::vector<double> v(100, 1.0);
  CHECK(scope.count() >= 2);
  stairplan::testing::AllocationScope none;
  v[3] = *p;
  CHECK(none.count() == 0);
}
