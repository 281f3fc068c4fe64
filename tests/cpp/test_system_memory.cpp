// The platform's memory query (system_memory.h) and the budget built on it (memory_budget.h): the
// figures must be known and plausible on every supported platform (a query that fails reads as
// kUnknownMemory, one that reads the wrong field as 0 or as more than the machine has), and
// GAUSS_MEMORY_BUDGET_MB must replace them exactly when it is a number and be ignored otherwise.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "gauss/util/memory_budget.h"
#include "gauss/util/system_memory.h"
#include "scoped_env.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_system_memory {

namespace {

constexpr int64_t kMiB = int64_t{1} << 20;

}  // namespace

TEST(SystemMemory, TotalIsKnownAndAPlausibleMachineSize) {
  const int64_t total = gauss::system_total_memory_bytes();
  ASSERT_NE(total, gauss::kUnknownMemory) << "the system's total memory could not be read";
  EXPECT_GE(total, 256 * kMiB);              // no machine that runs these tests has less
  EXPECT_LE(total, int64_t{1} << 50);        // nor more than a pebibyte
  EXPECT_EQ(total % 4096, 0) << total;       // physical memory is counted in whole pages
}

TEST(SystemMemory, AvailableIsKnownPositiveAndAtMostTheTotal) {
  const int64_t total = gauss::system_total_memory_bytes();
  const int64_t available = gauss::system_available_memory_bytes();
  ASSERT_NE(available, gauss::kUnknownMemory) << "the system's available memory could not be read";
  EXPECT_GE(available, 64 * kMiB);  // the suite itself needs more than that free
  EXPECT_LE(available, total);
}

TEST(SystemMemory, ReleaseFreeMemoryKeepsLiveBlocksIntact) {
  // Frees every other block of a fragmented heap, releases, and checks the survivors: a release that
  // returned pages still in use would show here (or crash).
  std::vector<std::vector<unsigned char>> blocks(2000);
  for (size_t i = 0; i < blocks.size(); ++i) blocks[i].assign(16 * 1024, static_cast<unsigned char>(i));
  for (size_t i = 0; i < blocks.size(); i += 2) std::vector<unsigned char>().swap(blocks[i]);
  gauss::release_free_memory();
  for (size_t i = 1; i < blocks.size(); i += 2)
    for (unsigned char c : blocks[i]) ASSERT_EQ(c, static_cast<unsigned char>(i)) << "block " << i;
}

TEST(MemoryBudget, EnvironmentBudgetReplacesTheSystemFigure) {
  {
    const gauss_test::ScopedEnv budget("GAUSS_MEMORY_BUDGET_MB", "1.5");
    EXPECT_EQ(gauss::available_memory_bytes(), 3 * kMiB / 2);
    EXPECT_NO_THROW(gauss::check_memory(kMiB, "a test"));
    EXPECT_THROW(gauss::check_memory(2 * kMiB, "a test"), gauss::OutOfMemory);
  }
  {
    const gauss_test::ScopedEnv budget("GAUSS_MEMORY_BUDGET_MB", "0");
    EXPECT_EQ(gauss::available_memory_bytes(), 0);
    EXPECT_THROW(gauss::check_memory(1, "a test"), gauss::OutOfMemory);
  }
}

TEST(MemoryBudget, EnvironmentBudgetThatIsNotANumberIsIgnored) {
  const int64_t total = gauss::system_total_memory_bytes();
  for (const char* value : {"abc", "-5", "1e13", " "}) {
    const gauss_test::ScopedEnv budget("GAUSS_MEMORY_BUDGET_MB", value);
    const int64_t available = gauss::available_memory_bytes();
    SCOPED_TRACE(std::string("GAUSS_MEMORY_BUDGET_MB='") + value + "'");
    EXPECT_GE(available, 64 * kMiB);  // the system's figure, as above
    EXPECT_LE(available, total);
  }
}

}  // namespace test_system_memory
