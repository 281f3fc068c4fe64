#pragma once
// What happens around one local-global step, whatever the method's local step is.
//
// A solver step is a map T on the vertices (the local step, the global solve, and Keep Volume if it is
// on). This class applies it, measures how far a run is from its fixed point, and accelerates it.
//
// reldV = max over coordinates |T(U) - U|  /  max over coordinates |T(U) - V|
// (U the vertices the step was applied to, V the rest mesh): the stopping rule of the reference cubic
// stylization code, so a tolerance means the same as there; for the plain iteration U is the previous
// step's result, so this is exactly "the largest change of a step over the largest displacement". It is
// invariant to translation and scale, so the solver's normalized frame gives the caller's value. One
// deviation: a displacement from the rest mesh below kStillDisplacement times the mesh's size counts
// as that much, because a mesh that does not move (a cube under the cube style) moves by rounding
// only (~1e-14) and the plain ratio of two rounding errors is noise.
//
// Acceleration (on by default: settings::acceleration). After the fast first steps the plain
// iteration creeps towards its fixed point along an almost fixed direction, each step a little shorter
// than the last, so it takes many steps to reach the tolerance. Momentum follows that direction: T is
// applied at
//   y_k = x_k + beta (x_k - x_{k-1})        (beta: the method's settings::Momentum)
// and x_{k+1} = T(y_k), a genuine step of Algorithm 1, is what the caller sees; reldV is measured from
// y_k, so it still says how far one plain step moves, divided by the method's stop_factor
// (settings::Momentum: where that understates it). Adaptive restart (O'Donoghue & Candes 2015,
// per vertex): a vertex whose step from y_k points against its momentum (a negative dot product) gets
// none for the next `hold` steps, so sliver regions that flap from step to step are not kicked
// further; when the dot product summed over all vertices is negative, all restart.
// Back-off: a restart after at most kShortMomentum extrapolated steps means the momentum bought
// nothing there; from the second such restart in a row the run takes 2, 4, 8, ... (at most
// kMaxPlainSteps) plain steps more than a restart's one before momentum comes back. Where the plain
// iteration does not creep but cycles or wanders (a mesh that is already the style's shape, under the
// cubic method; Tetrahedron at lambda 10 on meshes with slivers), momentum restarted at every other
// step turned the run into a cycle of its own, a plain and an extrapolated step, that moved the mesh
// by up to 1% of its size per step where the plain iteration settles or moves far less
// (docs/performance.md#converging-in-fewer-steps).
// A step that carries a state of its own from step to step (the cubic method's per-vertex ADMM
// state) is a map on the vertices and that state together: both are extrapolated, each vertex's
// state with the vertex, because momentum on the vertices alone stopped the cubic method short of the
// plain result. The steps saved, the converged shares against the plain iteration's and the
// alternatives that lost (Anderson acceleration, over-relaxation) are measured in
// docs/performance.md#converging-in-fewer-steps.
//
// Usage (X: the solver's current vertices, #V by 3):
//   FixedPointIteration it(num_vertices);
//   it.advance(X, rest, size, [&] { local_step(); global_step(); });   // per step, no allocation
//   or, for a step with a carried state S (#V by k; it.prepare_carried(S.size()) once beforehand):
//   it.advance(X, S, rest, size, [&] { ... });
//   it.last_reldv();   // +infinity before the first step and after invalidate()
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gauss/settings.h"

namespace gauss {

// Relative displacement below which a mesh counts as not moved (see above).
inline constexpr double kStillDisplacement = 1e-8;
// The back-off (see above): a restart after at most this many extrapolated steps is a short one...
inline constexpr int kShortMomentum = 3;
// ...and the most plain steps in a row it imposes.
inline constexpr int kMaxPlainSteps = 32;

// reldV of one step from `from` to `to`.
//   from, to, rest  #V by 3, one frame;  size  the mesh's extent in that frame (> 0)
// Returns 0 if nothing moved.
double relative_change(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                       const std::vector<Eigen::Vector3d>& rest, double size);

class FixedPointIteration {
 public:
  FixedPointIteration() = default;
  explicit FixedPointIteration(int num_vertices);

  // One iteration: X := T(y) with y = X (plain) or the momentum point (accelerated), where step()
  // applies T to X in place. rest: #V by 3, the rest mesh; size: its extent.
  template <class Step>
  void advance(std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector3d>& rest, double size, Step&& step) {
    advance(X, no_carried_state_, rest, size, step);
  }
  // The same for a step that also reads and writes a state of its own, carried from step to step
  // (carried: #V by k, vertex v's rows [k v, k v + k), at most prepare_carried()'s size): it is
  // extrapolated together with the vertices. Its size may change between steps (a change of method)
  // only after invalidate() or set_acceleration(): the momentum of another state means nothing.
  template <class Step>
  void advance(std::vector<Eigen::Vector3d>& X, std::vector<Eigen::Vector3d>& carried,
               const std::vector<Eigen::Vector3d>& rest, double size, Step&& step) {
    move_to_momentum_point(X, carried);  // X := y, point_ := y, current_ := x_k
    step();
    last_reldv_ = relative_change(point_, X, rest, size);
    if (extrapolated_) last_reldv_ /= momentum_.stop_factor;
    if (accelerate_) update_momentum(X, carried);
  }

  // reldV of the last step; +infinity before the first step and after invalidate().
  double last_reldv() const { return last_reldv_; }
  // The map or the iterate changed (a setting, the pins, new vertices, a reset): whatever the last
  // step measured no longer says how far the run is from its fixed point, and the momentum is stale.
  void invalidate() {
    last_reldv_ = INFINITY;
    restart();
    forget_backoff();
  }

  // Sizes the buffers for a carried state of up to `size` rows (allocates; not during a step).
  void prepare_carried(size_t size);
  // Bytes prepare_carried(size) allocates.
  static int64_t carried_bytes(size_t size) { return 2 * static_cast<int64_t>(size * sizeof(Eigen::Vector3d)); }

  void set_acceleration(bool on, settings::Momentum momentum) {
    accelerate_ = on;
    momentum_ = momentum;
    restart();
    forget_backoff();
  }
  bool acceleration() const { return accelerate_; }
  const settings::Momentum& momentum() const { return momentum_; }
  // Whether the step now running (or the last one) was applied at an extrapolated point, where the
  // step's residuals say as much about the extrapolation as about the step.
  bool extrapolated() const { return extrapolated_; }

 private:
  void restart();
  void forget_backoff() {
    short_restarts_ = 0;
    plain_steps_left_ = 0;
  }
  void move_to_momentum_point(std::vector<Eigen::Vector3d>& X, std::vector<Eigen::Vector3d>& carried);
  void update_momentum(const std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector3d>& carried);

  bool accelerate_ = settings::acceleration.default_value;
  settings::Momentum momentum_ = settings::gauss_momentum;
  bool has_momentum_ = false;
  bool extrapolated_ = false;
  double last_reldv_ = INFINITY;
  int momentum_steps_ = 0;    // extrapolated steps since momentum last (re)started
  int short_restarts_ = 0;    // restarts in a row that came after at most kShortMomentum of them
  int plain_steps_left_ = 0;  // plain steps the back-off still imposes
  // #V each, allocated once.
  std::vector<Eigen::Vector3d> point_;     // y: where the last step applied T
  std::vector<Eigen::Vector3d> current_;   // x_k: the iterate before the last step
  std::vector<Eigen::Vector3d> velocity_;  // x_k - x_{k-1}, then x_{k+1} - x_k
  std::vector<double> agreement_;          // (T(y) - y) . velocity per vertex
  std::vector<uint8_t> hold_;              // steps a vertex goes on without momentum
  // The same for a carried state (up to prepare_carried()'s size).
  std::vector<Eigen::Vector3d> carried_current_, carried_velocity_;
  std::vector<Eigen::Vector3d> no_carried_state_;  // empty
};

}  // namespace gauss
