#include "apps/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

// The counter sees every route to the heap the controller could take: operator new, and Eigen's
// dynamic matrices, which allocate through std::malloc.
TEST(AllocationCounter, CountsNewAndEigenAllocations) {
  long before = heap_allocations();
  auto p = std::make_unique<double[]>(8);
  EXPECT_EQ(heap_allocations() - before, 1);

  before = heap_allocations();
  Eigen::VectorXd v(1000);
  EXPECT_EQ(heap_allocations() - before, 1);

  before = heap_allocations();
  Eigen::Matrix<double, 6, 6> fixed = Eigen::Matrix<double, 6, 6>::Identity();
  std::vector<int> empty;
  v.setZero();
  p[0] = fixed(0, 0);
  EXPECT_EQ(heap_allocations() - before, 0) << "fixed-size and empty objects stay off the heap";
}
