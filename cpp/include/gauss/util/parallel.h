#pragma once
// The solver's data-parallel loops, run on a small pool of threads of its own instead of OpenMP.
//
// Why not OpenMP: the module must load in Blender builds that ship no OpenMP runtime, and GCC's
// libgomp cannot be linked statically into a shared object (it uses initial-exec TLS). Why this shape:
// every parallel loop of the solver is "split [0, n) into contiguous chunks, one per thread" or "run
// task t of a fixed number of tasks", with no reduction inside the loop.
//
// Determinism: each element of a loop is computed by the same operations whatever the chunking, and
// reductions happen outside the pool in a fixed order, so results do not depend on the thread count.
//
// Waiting: a step's loops come back to back, so workers spin for a short while (kSpinMicroseconds)
// before they sleep on a condition variable. An idle pool costs no CPU, and on a loaded machine a
// worker that was descheduled does not hold the others in a spinning barrier for long.
//
// Re-entrancy: one caller at a time uses the pool. A loop started while the pool is busy (another
// thread's solver, or a loop nested inside a loop body) runs serially on its caller, with the same
// result.
//
// Exceptions: a loop body that throws (an out-of-memory, a cancelled set-up) ends its own chunk; the
// other chunks run to their end, then the loop rethrows the first exception on its caller. Which
// elements of the loop were computed is then unspecified.
#include <algorithm>
#include <cstdint>

namespace gauss {
namespace parallel {

// The solver's loops pass this as min_parallel: below it forking costs more than it saves, and on a
// loaded machine (Blender's own threads) spinning workers can cost far more.
inline constexpr int kMinParallelItems = 4096;

// Threads loops use by default: GAUSS_THREADS or OMP_NUM_THREADS from the environment if set,
// otherwise the number of hardware threads.
int max_threads();
// Changes that default (n >= 1; larger values are capped at 256). Workers are started lazily.
void set_max_threads(int n);

// For the lifetime of this object, loops started by the calling thread use `threads` threads
// (capped at max_threads()); ThreadTuner's per-step choice between one thread and all.
class ScopedThreads {
 public:
  explicit ScopedThreads(int threads);
  ~ScopedThreads();
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int saved_;
};

// Threads the calling thread's loops would use now (ScopedThreads or max_threads()).
int current_threads();

namespace detail {
using ChunkFn = void (*)(void* context, int chunk, int num_chunks);
// Runs fn(context, c, num_chunks) for c in [0, num_chunks) on up to num_chunks threads, the calling
// thread taking chunk 0; returns when all are done. Serial if the pool is busy.
void run(ChunkFn fn, void* context, int num_chunks);
}  // namespace detail

// fn(begin, end) over contiguous ranges that cover [0, n), one per thread. Serial (one call
// fn(0, n)) when n < min_parallel or only one thread is to be used.
template <class F>
void for_ranges(int n, int min_parallel, F&& fn) {
  const int threads = std::min(current_threads(), n);
  if (n < min_parallel || threads <= 1) {
    if (n > 0) fn(0, n);
    return;
  }
  struct Context {
    F* fn;
    int n;
  } context{&fn, n};
  detail::run(
      [](void* c, int chunk, int chunks) {
        Context& ctx = *static_cast<Context*>(c);
        const int64_t begin = static_cast<int64_t>(ctx.n) * chunk / chunks;
        const int64_t end = static_cast<int64_t>(ctx.n) * (chunk + 1) / chunks;
        if (begin < end) (*ctx.fn)(static_cast<int>(begin), static_cast<int>(end));
      },
      &context, threads);
}

// fn(i) for every i in [0, n), split as in for_ranges.
template <class F>
void for_each(int n, int min_parallel, F&& fn) {
  for_ranges(n, min_parallel, [&fn](int begin, int end) {
    for (int i = begin; i < end; ++i) fn(i);
  });
}

// fn(task) for task in [0, count): task t runs on thread t % threads (OpenMP's schedule(static, 1)).
// Serial when `parallel` is false or only one thread is to be used.
template <class F>
void for_tasks(int count, bool parallel, F&& fn) {
  const int threads = std::min(current_threads(), count);
  if (!parallel || threads <= 1) {
    for (int t = 0; t < count; ++t) fn(t);
    return;
  }
  struct Context {
    F* fn;
    int count;
  } context{&fn, count};
  detail::run(
      [](void* c, int chunk, int chunks) {
        Context& ctx = *static_cast<Context*>(c);
        for (int t = chunk; t < ctx.count; t += chunks) (*ctx.fn)(t);
      },
      &context, threads);
}

}  // namespace parallel
}  // namespace gauss
