#pragma once
// What happens around one local-global step, whatever the method's local step is.
//
// A solver step is a map U_k = G(U_{k-1}) on the vertices (the local step, then the global solve).
// This class runs that map and measures how far a run is from its fixed point:
//
//   reldV = max over coordinates |U_k - U_{k-1}|  /  max over coordinates |U_k - V|
//
// (V the rest mesh): the stopping rule of the reference cubic stylization code, which issues 11 and 12
// adopt. It is invariant to translation and scale, so the solver's normalized frame gives the same
// value as the caller's. One deviation: a displacement from the rest mesh below kStillDisplacement
// times the mesh's size counts as that much, because a mesh that does not move (a cube under the cube
// style) moves by rounding only (~1e-14) and the plain ratio of two rounding errors is noise.
//
// Usage (X: the solver's current vertices, #V by 3):
//   FixedPointIteration it(num_vertices);
//   it.advance(X, rest, size, [&] { local_step(); global_step(); });   // per step, no allocation
//   it.last_reldv();   // +infinity before the first step and after invalidate()
#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace gauss {

// Relative displacement below which a mesh counts as not moved (see above).
inline constexpr double kStillDisplacement = 1e-8;

// reldV of one step.
//   previous, current, rest  #V by 3, one frame;  size  the mesh's extent in that frame (> 0)
// Returns 0 if nothing moved.
double relative_change(const std::vector<Eigen::Vector3d>& previous, const std::vector<Eigen::Vector3d>& current,
                       const std::vector<Eigen::Vector3d>& rest, double size);

class FixedPointIteration {
 public:
  FixedPointIteration() = default;
  explicit FixedPointIteration(int num_vertices) : previous_(num_vertices) {}

  // One iteration: X := step(X), where step() updates X in place (it is the caller's local and
  // global step on X). rest: #V by 3, the rest mesh; size: its extent.
  template <class Step>
  void advance(std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector3d>& rest, double size, Step&& step) {
    previous_ = X;  // same size: no allocation
    step();
    last_reldv_ = relative_change(previous_, X, rest, size);
  }

  // reldV of the last step; +infinity before the first step and after invalidate().
  double last_reldv() const { return last_reldv_; }
  // The map or the iterate changed (a setting, the pins, new vertices, a reset): whatever the last
  // step measured no longer says how far the run is from its fixed point.
  void invalidate() { last_reldv_ = INFINITY; }

 private:
  std::vector<Eigen::Vector3d> previous_;  // #V: the iterate before the step
  double last_reldv_ = INFINITY;
};

}  // namespace gauss
