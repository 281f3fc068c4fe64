#pragma once
// Picks, from measured step times, whether the next step runs on all threads or on one.
//
// Why: a parallel loop waits for its slowest thread. When other processes hold the cores (a render,
// a compile, Blender's own jobs), a descheduled worker stalls every loop of the step; with OpenMP's
// spinning barriers a step on 2 threads can be many times slower than on 1 (measured:
// docs/performance.md#figures-behind-the-codes-choices).
// Steps are bit-identical for any thread count, so choosing by speed never changes a result.
// Policy: try both, then keep the faster (with 10% hysteresis) and re-try the other one every
// kProbeInterval steps, so the choice follows the machine's load.
#include <algorithm>

namespace gauss {

class ThreadTuner {
 public:
  // The thread count for the next step, 1 or max_threads.
  int next(int max_threads) {
    if (max_threads <= 1) return 1;
    ++steps_;
    if (ms_[0] < 0) return 1;                      // first step: measure one thread
    if (ms_[1] < 0) return max_threads;            // second: measure all threads
    const bool many_faster = ms_[1] < (use_many_ ? 1.1 : 0.9) * ms_[0];
    use_many_ = many_faster;
    if (steps_ % kProbeInterval == 0) return use_many_ ? 1 : max_threads;  // re-check the other
    return use_many_ ? max_threads : 1;
  }
  void record(int threads, double ms) {
    double& m = ms_[threads > 1 ? 1 : 0];
    m = m < 0 ? ms : 0.7 * m + 0.3 * ms;
  }
  void reset() { *this = ThreadTuner(); }

 private:
  static constexpr int kProbeInterval = 25;
  double ms_[2] = {-1.0, -1.0};  // running mean step time: one thread, all threads
  bool use_many_ = true;
  long steps_ = 0;
};

}  // namespace gauss
