#include "gauss/util/parallel.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)  // GCC/Clang, MSVC
#include <immintrin.h>
#define GAUSS_CPU_RELAX() _mm_pause()
#else
#define GAUSS_CPU_RELAX() std::this_thread::yield()
#endif

namespace gauss {
namespace parallel {
namespace {

// How long a worker (or the caller, waiting for the workers) spins before it sleeps. Long enough to
// bridge the serial pieces between a step's loops, short enough not to matter on a busy machine.
constexpr int kSpinMicroseconds = 1000;
constexpr int kMaxThreads = 256;

using Clock = std::chrono::steady_clock;

// Spins until done() or the spin time is over; true if done().
template <class Done>
bool spin_until(Done&& done) {
  const auto deadline = Clock::now() + std::chrono::microseconds(kSpinMicroseconds);
  for (int i = 1;; ++i) {
    if (done()) return true;
    GAUSS_CPU_RELAX();
    if ((i & 63) == 0 && Clock::now() > deadline) return done();
  }
}

int threads_from_environment() {
  for (const char* name : {"GAUSS_THREADS", "OMP_NUM_THREADS"}) {
    const char* value = std::getenv(name);
    if (value != nullptr) {
      const int n = std::atoi(value);
      if (n >= 1) return std::min(n, kMaxThreads);
    }
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(std::min<unsigned>(hw, kMaxThreads));
}

std::atomic<int> g_max_threads{0};  // 0: not read from the environment yet
thread_local int t_scoped_threads = 0;  // 0: no ScopedThreads on this thread

// One worker thread. Each has its own ticket and wake-up, so a job wakes exactly the workers it
// uses, and a worker never reads the job description of a job it was not given.
struct alignas(64) Worker {
  std::atomic<uint64_t> ticket{0};
  std::atomic<bool> sleeping{false};
  std::mutex mutex;
  std::condition_variable wake;
  std::thread thread;
};

class Pool {
 public:
  // Never destroyed (see pool()): workers sleep in wait() when the process exits.
  void run(detail::ChunkFn fn, void* context, int chunks) {
    bool expected = false;
    if (chunks <= 1 || !busy_.compare_exchange_strong(expected, true, std::memory_order_acquire)) {
      for (int c = 0; c < chunks; ++c) fn(context, c, chunks);  // busy or nested: serial, same result
      return;
    }
    grow(chunks - 1);
    fn_ = fn;
    context_ = context;
    chunks_ = chunks;
    remaining_.store(chunks - 1, std::memory_order_relaxed);
    for (int w = 0; w < chunks - 1; ++w) {
      Worker& worker = *workers_[w];
      worker.ticket.fetch_add(1, std::memory_order_seq_cst);  // publishes the job fields above
      if (worker.sleeping.load(std::memory_order_seq_cst)) {
        { std::lock_guard<std::mutex> lock(worker.mutex); }
        worker.wake.notify_one();
      }
    }
    call(fn, context, 0, chunks);
    if (!spin_until([&] { return remaining_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock<std::mutex> lock(done_mutex_);
      done_.wait(lock, [&] { return remaining_.load(std::memory_order_acquire) == 0; });
    }
    // Every chunk has ended (the context lives on the caller's stack), so the job's first exception,
    // if any, can be rethrown here.
    std::exception_ptr error;
    {
      std::lock_guard<std::mutex> lock(error_mutex_);
      error = error_;  // (no exception_ptr::swap in libc++)
      error_ = nullptr;
    }
    busy_.store(false, std::memory_order_release);
    if (error) std::rethrow_exception(error);
  }

 private:
  void grow(int count) {  // only while busy_: no job is running
    while (static_cast<int>(workers_.size()) < count) {
      const int index = static_cast<int>(workers_.size());
      workers_.push_back(std::make_unique<Worker>());
      Worker* worker = workers_.back().get();  // stable: the vector holds pointers
      worker->thread = std::thread([this, worker, index] { work(*worker, index); });
      worker->thread.detach();
    }
  }

  void work(Worker& self, int index) {
    uint64_t seen = 0;
    for (;;) {
      auto given = [&] { return self.ticket.load(std::memory_order_seq_cst) != seen; };
      if (!spin_until(given)) {
        std::unique_lock<std::mutex> lock(self.mutex);
        self.sleeping.store(true, std::memory_order_seq_cst);
        self.wake.wait(lock, given);
        self.sleeping.store(false, std::memory_order_relaxed);
      }
      seen = self.ticket.load(std::memory_order_acquire);
      call(fn_, context_, index + 1, chunks_);
      if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        { std::lock_guard<std::mutex> lock(done_mutex_); }
        done_.notify_one();
      }
    }
  }

  // Runs one chunk; an exception is kept for run() to rethrow (the first one wins), never let out of a
  // worker thread, where it would end the process.
  void call(detail::ChunkFn fn, void* context, int chunk, int chunks) noexcept {
    try {
      fn(context, chunk, chunks);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }

  std::atomic<bool> busy_{false};
  std::vector<std::unique_ptr<Worker>> workers_;
  detail::ChunkFn fn_ = nullptr;
  void* context_ = nullptr;
  int chunks_ = 0;
  std::atomic<int> remaining_{0};
  std::mutex done_mutex_;
  std::condition_variable done_;
  std::mutex error_mutex_;
  std::exception_ptr error_;  // the running job's first exception
};

Pool& pool() {
  static Pool* instance = new Pool;  // intentionally leaked: no teardown races at process exit
  return *instance;
}

}  // namespace

int max_threads() {
  int n = g_max_threads.load(std::memory_order_relaxed);
  if (n == 0) {
    n = threads_from_environment();
    int expected = 0;
    if (!g_max_threads.compare_exchange_strong(expected, n)) n = expected;
  }
  return n;
}

void set_max_threads(int n) { g_max_threads.store(std::max(1, std::min(n, kMaxThreads))); }

int current_threads() {
  const int m = max_threads();
  return t_scoped_threads > 0 ? std::min(t_scoped_threads, m) : m;
}

ScopedThreads::ScopedThreads(int threads) : saved_(t_scoped_threads) { t_scoped_threads = std::max(1, threads); }
ScopedThreads::~ScopedThreads() { t_scoped_threads = saved_; }

namespace detail {
void run(ChunkFn fn, void* context, int num_chunks) { pool().run(fn, context, num_chunks); }
}  // namespace detail

}  // namespace parallel
}  // namespace gauss
