// The solver's thread pool (parallel.h): every index visited exactly once for any range, threshold and
// thread count; task t on thread t % threads; loops nested or started from two threads at once still
// run whole; per-element results the same for any thread count; an exception reaches the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gauss/util/parallel.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_parallel {

namespace {

// Raises the pool's default for one test (so that 4 and 8 threads are real on a 2-core machine) and
// puts the previous default back.
class ScopedMaxThreads {
 public:
  explicit ScopedMaxThreads(int n) : saved_(gauss::parallel::max_threads()) { gauss::parallel::set_max_threads(n); }
  ~ScopedMaxThreads() { gauss::parallel::set_max_threads(saved_); }

 private:
  int saved_;
};

const int kThreadCounts[] = {1, 2, 3, 4, 8};

}  // namespace

TEST(Parallel, ForEachVisitsEveryIndexOnce) {
  ScopedMaxThreads max(8);
  for (int threads : kThreadCounts) {
    gauss::parallel::ScopedThreads scoped(threads);
    EXPECT_EQ(gauss::parallel::current_threads(), threads);
    for (int n : {0, 1, 2, 3, 7, 8, 9, 100, 4096, 10007})
      for (int min_parallel : {0, 2, n, n + 1}) {
        SCOPED_TRACE("threads " + std::to_string(threads) + ", n " + std::to_string(n) + ", min_parallel " +
                     std::to_string(min_parallel));
        std::unique_ptr<std::atomic<int>[]> visits(new std::atomic<int>[n + 1]);
        for (int i = 0; i <= n; ++i) visits[i] = 0;
        gauss::parallel::for_each(n, min_parallel, [&](int i) {
          if (i >= 0 && i < n) ++visits[i];
          else ++visits[n];  // out of range
        });
        for (int i = 0; i < n; ++i) ASSERT_EQ(visits[i].load(), 1) << "index " << i;
        EXPECT_EQ(visits[n].load(), 0);
      }
  }
}

TEST(Parallel, ForRangesCoversTheRangeWithDisjointNonEmptyRanges) {
  ScopedMaxThreads max(8);
  for (int threads : kThreadCounts) {
    gauss::parallel::ScopedThreads scoped(threads);
    for (int n : {0, 1, 2, 5, 8, 1000}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", n " + std::to_string(n));
      std::mutex mutex;
      std::map<int, int> ranges;  // begin -> end
      gauss::parallel::for_ranges(n, 0, [&](int begin, int end) {
        std::lock_guard<std::mutex> lock(mutex);
        ranges[begin] = end;
      });
      if (n == 0) {
        EXPECT_TRUE(ranges.empty());
        continue;
      }
      EXPECT_LE(static_cast<int>(ranges.size()), threads);
      int next = 0;
      for (const auto& r : ranges) {
        EXPECT_EQ(r.first, next);
        EXPECT_LT(r.first, r.second);
        next = r.second;
      }
      EXPECT_EQ(next, n);
    }
  }
}

TEST(Parallel, ForTasksRunsTaskTOnThreadTModThreads) {
  ScopedMaxThreads max(8);
  for (int threads : kThreadCounts)
    for (int count : {0, 1, 3, 8, 17}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", count " + std::to_string(count));
      gauss::parallel::ScopedThreads scoped(threads);
      std::vector<std::thread::id> ran_on(count);
      std::vector<int> runs(count, 0);
      gauss::parallel::for_tasks(count, true, [&](int t) {
        ran_on[t] = std::this_thread::get_id();
        ++runs[t];  // each task written by one thread only
      });
      const int used = std::min(threads, count);
      for (int t = 0; t < count; ++t) {
        EXPECT_EQ(runs[t], 1) << "task " << t;
        EXPECT_EQ(ran_on[t], ran_on[t % used]) << "task " << t;
        if (t < used && t > 0) EXPECT_NE(ran_on[t], ran_on[0]) << "task " << t;
      }
      if (count > 0) EXPECT_EQ(ran_on[0], std::this_thread::get_id());  // chunk 0: the caller
      // Not parallel: everything on the caller, in order.
      const std::thread::id caller = std::this_thread::get_id();
      std::vector<int> order;
      gauss::parallel::for_tasks(count, false, [&](int t) {
        EXPECT_EQ(std::this_thread::get_id(), caller);
        order.push_back(t);
      });
      for (int t = 0; t < count; ++t) EXPECT_EQ(order[t], t);
    }
}

TEST(Parallel, ResultsDoNotDependOnTheThreadCount) {
  ScopedMaxThreads max(8);
  const int n = 50000;
  std::vector<double> reference;
  for (int threads : kThreadCounts) {
    gauss::parallel::ScopedThreads scoped(threads);
    std::vector<double> out(n);
    gauss::parallel::for_each(n, gauss::parallel::kMinParallelItems, [&](int i) {
      double x = 0.0;
      for (int k = 1; k <= 20; ++k) x += std::sin(i * 0.001 * k) / k;
      out[i] = x;
    });
    if (reference.empty())
      reference = out;
    else
      EXPECT_EQ(std::memcmp(out.data(), reference.data(), sizeof(double) * n), 0) << "threads " << threads;
  }
}

TEST(Parallel, NestedAndConcurrentLoopsRunWhole) {
  ScopedMaxThreads max(4);
  gauss::parallel::ScopedThreads scoped(4);
  // A loop inside a loop body runs serially on its caller, every inner index once.
  const int outer = 8, inner = 5000;
  std::vector<std::atomic<int>> hits(outer * inner);
  for (auto& h : hits) h = 0;
  gauss::parallel::for_each(outer, 0, [&](int o) {
    gauss::parallel::for_each(inner, 0, [&](int i) { ++hits[o * inner + i]; });
  });
  for (int k = 0; k < outer * inner; ++k) ASSERT_EQ(hits[k].load(), 1) << "index " << k;

  // Two threads using the pool at once (two solvers): both loops complete, each index once.
  const int n = 20000;
  std::vector<std::atomic<int>> a(n), b(n);
  for (int i = 0; i < n; ++i) a[i] = b[i] = 0;
  auto many_loops = [n](std::vector<std::atomic<int>>& v) {
    gauss::parallel::ScopedThreads threads(4);
    for (int round = 0; round < 50; ++round) gauss::parallel::for_each(n, 0, [&](int i) { ++v[i]; });
  };
  std::thread other([&] { many_loops(b); });
  many_loops(a);
  other.join();
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(a[i].load(), 50) << "index " << i;
    ASSERT_EQ(b[i].load(), 50) << "index " << i;
  }
}

TEST(Parallel, ScopedThreadsIsCappedAndRestored) {
  ScopedMaxThreads max(3);
  EXPECT_EQ(gauss::parallel::max_threads(), 3);
  EXPECT_EQ(gauss::parallel::current_threads(), 3);
  {
    gauss::parallel::ScopedThreads one(1);
    EXPECT_EQ(gauss::parallel::current_threads(), 1);
    {
      gauss::parallel::ScopedThreads many(100);
      EXPECT_EQ(gauss::parallel::current_threads(), 3);
    }
    EXPECT_EQ(gauss::parallel::current_threads(), 1);
  }
  EXPECT_EQ(gauss::parallel::current_threads(), 3);
  gauss::parallel::set_max_threads(1000);
  EXPECT_EQ(gauss::parallel::max_threads(), 256);
}

// A throw in any chunk (a worker's or the caller's) reaches the loop's caller once every chunk has
// ended, the other chunks still run, and the pool takes the next loop as before.
TEST(Parallel, AnExceptionInAnyChunkReachesTheCallerAndThePoolStaysUsable) {
  ScopedMaxThreads max(4);
  const int n = 40000;
  for (int threads : kThreadCounts) {
    gauss::parallel::ScopedThreads scoped(threads);
    for (int thrower : {0, n / 2, n - 1}) {  // in the caller's chunk (0), a worker's, the last worker's
      std::vector<std::atomic<int>> hits(n);
      for (auto& h : hits) h = 0;
      std::string message;
      try {
        gauss::parallel::for_each(n, 0, [&](int i) {
          if (i == thrower) throw std::runtime_error("element " + std::to_string(i));
          ++hits[i];
        });
      } catch (const std::runtime_error& e) {
        message = e.what();
      }
      EXPECT_EQ(message, "element " + std::to_string(thrower)) << threads << " threads";
      // Every other chunk ran to its end (chunks as for_ranges cuts them).
      const int chunks = gauss::parallel::current_threads();
      const int own = static_cast<int>(static_cast<int64_t>(thrower) * chunks / n);
      for (int c = 0; c < chunks; ++c) {
        if (c == own) continue;
        for (int64_t i = int64_t{n} * c / chunks; i < int64_t{n} * (c + 1) / chunks; ++i)
          ASSERT_EQ(hits[i].load(), 1) << "index " << i << ", " << threads << " threads";
      }
      EXPECT_EQ(hits[thrower].load(), 0);

      std::vector<std::atomic<int>> again(n);
      for (auto& h : again) h = 0;
      gauss::parallel::for_each(n, 0, [&](int i) { ++again[i]; });
      for (int i = 0; i < n; ++i) ASSERT_EQ(again[i].load(), 1) << "index " << i << ", " << threads << " threads";
    }
  }
  // Tasks too, where every task throws: one exception comes out.
  gauss::parallel::ScopedThreads scoped(4);
  EXPECT_THROW(gauss::parallel::for_tasks(4, true, [](int t) { throw std::out_of_range(std::to_string(t)); }),
               std::out_of_range);
}

}  // namespace test_parallel
