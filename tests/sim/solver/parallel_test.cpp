#include "sim/solver/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

using namespace ligsim::sim;

TEST(ParallelTasks, EveryTaskRunsOnceAndTheFirstErrorComesBackAfterAllEnded)
{
  std::vector<int> runs(5, 0);
  parallel_tasks(runs.size(), [&](std::size_t i) { ++runs[i]; });
  EXPECT_EQ(runs, std::vector<int>(5, 1));

  std::atomic<int> ended{0};
  const auto failing = [&](std::size_t i) {
    ++ended;
    if (i == 2 || i == 3)
      throw std::runtime_error("task " + std::to_string(i));
  };
  try {
    parallel_tasks(4, failing);
    FAIL() << "no error came back";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 2");
  }
  EXPECT_EQ(ended.load(), 4);
}
