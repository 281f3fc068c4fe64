#include "gauss/solver/fixed_point_iteration.h"

#include <algorithm>
#include <stdexcept>

#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Vector3d;

double relative_change(const std::vector<Vector3d>& from, const std::vector<Vector3d>& to,
                       const std::vector<Vector3d>& rest, double size) {
  // Maxima do not depend on the order they are taken in: serial is as deterministic as it is cheap
  // (two passes over #V; its share of a step: docs/performance.md#figures-behind-the-codes-choices).
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
      velocity_(num_vertices, Vector3d::Zero()),
      agreement_(num_vertices, 0.0),
      hold_(num_vertices, 0) {}

void FixedPointIteration::prepare_carried(size_t size) {
  if (size > carried_velocity_.size()) {
    carried_current_.resize(size);
    carried_velocity_.resize(size, Vector3d::Zero());
  }
  restart();
}

void FixedPointIteration::restart() {
  has_momentum_ = false;
  momentum_steps_ = 0;
  std::fill(hold_.begin(), hold_.end(), 0);
}

void FixedPointIteration::move_to_momentum_point(std::vector<Vector3d>& X, std::vector<Vector3d>& carried) {
  const int n = static_cast<int>(X.size());
  if (carried.size() > carried_velocity_.size())
    throw std::logic_error("FixedPointIteration: the carried state is larger than prepare_carried() made room for");
  extrapolated_ = accelerate_ && has_momentum_;
  if (!extrapolated_) {
    point_ = X;  // same sizes: no allocation
    if (accelerate_) {
      current_ = X;
      std::copy(carried.begin(), carried.end(), carried_current_.begin());
    }
    return;
  }
  const double beta = momentum_.beta;
  const int k = n > 0 ? static_cast<int>(carried.size()) / n : 0;
  parallel::for_each(n, parallel::kMinParallelItems, [&](int v) {
    current_[v] = X[v];
    for (int j = k * v; j < k * v + k; ++j) carried_current_[j] = carried[j];
    if (hold_[v] == 0) {
      X[v] += beta * velocity_[v];
      for (int j = k * v; j < k * v + k; ++j) carried[j] += beta * carried_velocity_[j];
    }
    point_[v] = X[v];
  });
}

void FixedPointIteration::update_momentum(const std::vector<Vector3d>& X, const std::vector<Vector3d>& carried) {
  if (plain_steps_left_ > 0) {  // backing off: the next step is plain too
    --plain_steps_left_;
    return;
  }
  const int n = static_cast<int>(X.size());
  const bool had_momentum = has_momentum_;
  const int k = n > 0 ? static_cast<int>(carried.size()) / n : 0;
  parallel::for_each(n, parallel::kMinParallelItems, [&](int v) {
    if (had_momentum) {
      agreement_[v] = (X[v] - point_[v]).dot(velocity_[v]);
      if (agreement_[v] < 0) hold_[v] = static_cast<uint8_t>(momentum_.hold);
      else if (hold_[v] > 0) --hold_[v];
    }
    velocity_[v] = X[v] - current_[v];
    for (int j = k * v; j < k * v + k; ++j) carried_velocity_[j] = carried[j] - carried_current_[j];
  });
  has_momentum_ = true;
  if (!had_momentum) return;
  double total = 0;  // serial: the same sum for any thread count
  for (double a : agreement_) total += a;
  ++momentum_steps_;
  if (total < 0) {
    short_restarts_ = momentum_steps_ <= kShortMomentum ? short_restarts_ + 1 : 0;
    restart();
    if (short_restarts_ >= 2) plain_steps_left_ = std::min(1 << std::min(short_restarts_ - 1, 30), kMaxPlainSteps);
  }
}

}  // namespace gauss
