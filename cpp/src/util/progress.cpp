#include "gauss/util/progress.h"

#include <algorithm>
#include <chrono>

namespace gauss {
namespace {

constexpr int kPhases = static_cast<int>(SetupPhase::count);

// Share of each phase in the set-up time of a big mesh, so that the fraction follows the clock; only
// the proportions matter (measured: docs/performance.md#set-up-at-scale).
constexpr double kPhaseWeight[kPhases] = {
    /* topology */ 0.05,
    /* weights */ 0.07,
    /* ordering */ 0.40,
    /* symbolic */ 0.05,
    /* factorizing */ 0.43,
};

constexpr const char* kPhaseName[kPhases] = {"topology", "weights", "ordering", "symbolic", "factorizing"};

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

const char* phase_name(SetupPhase phase) {
  const int p = static_cast<int>(phase);
  return p >= 0 && p < kPhases ? kPhaseName[p] : "";
}

const char* Progress::phase() const {
  const int p = phase_.load(std::memory_order_relaxed);
  if (p < 0) return "";
  return p >= kPhases ? "done" : kPhaseName[p];
}

double Progress::seconds(SetupPhase phase) const {
  const int p = static_cast<int>(phase);
  return p >= 0 && p < kPhases ? seconds_[p].load(std::memory_order_relaxed) : 0.0;
}

void Progress::start(SetupPhase first) {
  check();
  const int f = static_cast<int>(first);
  double total = 0;
  for (int p = f; p < kPhases; ++p) total += kPhaseWeight[p];
  double at = 0;
  for (int p = 0; p <= kPhases; ++p) {
    slice_start_[p] = std::min(at / total, 1.0);
    if (p >= f && p < kPhases) at += kPhaseWeight[p];
  }
  for (auto& s : seconds_) s.store(0.0, std::memory_order_relaxed);
  fraction_.store(0.0, std::memory_order_relaxed);
  phase_.store(f, std::memory_order_relaxed);
  phase_began_ = now_seconds();
}

void Progress::close_phase() {
  const int p = phase_.load(std::memory_order_relaxed);
  const double t = now_seconds();
  if (p >= 0 && p < kPhases) seconds_[p].store(seconds_[p].load(std::memory_order_relaxed) + t - phase_began_);
  phase_began_ = t;
}

void Progress::enter(SetupPhase phase) {
  check();
  close_phase();
  const int p = static_cast<int>(phase);
  phase_.store(p, std::memory_order_relaxed);
  raise_fraction(slice_start_[p]);
}

void Progress::advance(double done) {
  const int p = phase_.load(std::memory_order_relaxed);
  if (p < 0 || p >= kPhases) return;
  const double d = std::clamp(done, 0.0, 1.0);
  raise_fraction(slice_start_[p] + d * (slice_start_[p + 1] - slice_start_[p]));
}

void Progress::finish() {
  close_phase();
  phase_.store(kPhases, std::memory_order_relaxed);
  raise_fraction(1.0);
}

void Progress::raise_fraction(double f) {
  double cur = fraction_.load(std::memory_order_relaxed);
  while (f > cur && !fraction_.compare_exchange_weak(cur, f, std::memory_order_relaxed)) {
  }
}

}  // namespace gauss
