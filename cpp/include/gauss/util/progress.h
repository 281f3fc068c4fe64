#pragma once
// Progress and cancellation of a set-up (GaussSolver's constructor, set_pins' re-factorization),
// shared between the thread that runs the set-up and any thread that watches it (the add-on polls
// it from Blender's UI timer while a Python thread runs the constructor).
//
// The set-up walks through the phases of SetupPhase in order (a re-factorization only through the
// last four). fraction() moves from 0 to 1 and never goes back; each phase owns a slice of it as
// wide as its share of the set-up time (kPhaseWeight in progress.cpp), and within a phase the code
// reports how much of its work is done, so the fraction grows roughly in proportion to time.
//
// cancel() may be called from any thread; the set-up notices it at its next check (checks are a few
// milliseconds of work apart) and throws Cancelled after releasing everything it allocated.
//
// Every member is safe to call from any thread while a set-up runs.
#include <atomic>
#include <stdexcept>

namespace gauss {

// Thrown by a set-up whose Progress was cancelled (gauss_core.Cancelled in Python).
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("the set-up was cancelled") {}
};

// The phases of a set-up, in the order they run.
enum class SetupPhase : int {
  topology,     // validation, spatial renumbering, edges, adjacency, components
  weights,      // normalization, cotangent weights, per-face buffers, the Laplacian
  ordering,     // fill-reducing ordering (nested dissection)
  symbolic,     // elimination tree, supernodes, structure of the factor, memory check
  factorizing,  // numeric factorization
  count
};
const char* phase_name(SetupPhase phase);  // "topology", "weights", "ordering", "symbolic", "factorizing"

class Progress {
 public:
  // --- For the watcher. ---
  double fraction() const { return fraction_.load(std::memory_order_relaxed); }  // 0..1
  // "" before the set-up starts, then the current phase's name, "done" at the end.
  const char* phase() const;
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  // Seconds the last (or current) set-up spent in a phase; 0 for phases it did not run.
  double seconds(SetupPhase phase) const;
  // True between start() and finish().
  bool running() const {
    const int p = phase_.load(std::memory_order_relaxed);
    return p >= 0 && p < static_cast<int>(SetupPhase::count);
  }

  // --- For the set-up code. ---
  // Starts a set-up that runs the phases [first, SetupPhase::count): fraction 0, timings cleared.
  // Throws Cancelled if cancel() was called before (a cancelled Progress stays cancelled).
  void start(SetupPhase first);
  // Enters a phase (ends the previous one): the fraction jumps to the start of its slice. Throws
  // Cancelled if cancel() was called.
  void enter(SetupPhase phase);
  // Reports that `done` (0..1) of the current phase's work is finished. Thread-safe, so workers of a
  // parallel phase may report directly; the fraction only ever grows.
  void advance(double done);
  // Ends the set-up: fraction 1, phase "done".
  void finish();
  // Throws Cancelled if cancel() was called. Parallel workers must not throw: they test cancelled()
  // and stop, and the thread that started them calls check() afterwards.
  void check() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  void raise_fraction(double f);
  void close_phase();

  std::atomic<double> fraction_{0.0};
  std::atomic<int> phase_{-1};  // -1: not started, SetupPhase::count: done
  std::atomic<bool> cancelled_{false};
  // Slice of the current set-up's fraction that each phase owns: [slice_start_[p], slice_start_[p+1]).
  double slice_start_[static_cast<int>(SetupPhase::count) + 1] = {};
  std::atomic<double> seconds_[static_cast<int>(SetupPhase::count)] = {};
  double phase_began_ = 0;  // steady-clock seconds when the current phase began
};

// A set-up without a watcher still goes through the same calls: `progress ? *progress : unwatched`.
// Each call site owns its fallback so concurrent set-ups never share one.

}  // namespace gauss
