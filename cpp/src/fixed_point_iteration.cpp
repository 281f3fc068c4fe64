#include "gauss/fixed_point_iteration.h"

#include <algorithm>

#include "gauss/parallel.h"

namespace gauss {

using Eigen::Vector3d;

double relative_change(const std::vector<Vector3d>& from, const std::vector<Vector3d>& to,
                       const std::vector<Vector3d>& rest, double size) {
  // Maxima do not depend on the order they are taken in: serial is as deterministic as it is cheap
  // (two passes over #V, ~1% of a step).
  double change = 0.0, displacement = 0.0;
  const size_t n = to.size();
  for (size_t v = 0; v < n; ++v) {
    change = std::max(change, (to[v] - from[v]).cwiseAbs().maxCoeff());
    displacement = std::max(displacement, (to[v] - rest[v]).cwiseAbs().maxCoeff());
  }
  if (change == 0.0) return 0.0;
  displacement = std::max(displacement, kStillDisplacement * size);
  return change / displacement;
}

FixedPointIteration::FixedPointIteration(int num_vertices)
    : point_(num_vertices),
      current_(num_vertices),
      momentum_(num_vertices, Vector3d::Zero()),
      agreement_(num_vertices, 0.0),
      hold_(num_vertices, 0) {}

void FixedPointIteration::restart() {
  has_momentum_ = false;
  std::fill(hold_.begin(), hold_.end(), 0);
}

void FixedPointIteration::move_to_momentum_point(std::vector<Vector3d>& X) {
  const int n = static_cast<int>(X.size());
  if (!(accelerate_ && has_momentum_)) {
    point_ = X;  // same sizes: no allocation
    if (accelerate_) current_ = X;
    return;
  }
  const double beta = settings::momentum;
  parallel::for_each(n, parallel::kMinParallelItems, [&](int v) {
    current_[v] = X[v];
    if (hold_[v] == 0) X[v] += beta * momentum_[v];
    point_[v] = X[v];
  });
}

void FixedPointIteration::update_momentum(const std::vector<Vector3d>& X) {
  const int n = static_cast<int>(X.size());
  const bool had_momentum = has_momentum_;
  parallel::for_each(n, parallel::kMinParallelItems, [&](int v) {
    if (had_momentum) {
      agreement_[v] = (X[v] - point_[v]).dot(momentum_[v]);
      if (agreement_[v] < 0) hold_[v] = static_cast<uint8_t>(settings::momentum_hold);
      else if (hold_[v] > 0) --hold_[v];
    }
    momentum_[v] = X[v] - current_[v];
  });
  has_momentum_ = true;
  if (!had_momentum) return;
  double total = 0;  // serial: the same sum for any thread count
  for (double a : agreement_) total += a;
  if (total < 0) restart();
}

}  // namespace gauss
