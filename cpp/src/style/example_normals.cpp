#include "gauss/style/example_normals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gauss {

using Eigen::Vector3d;

namespace {

// Builds the k-d tree over order[begin, end): the middle element splits on the axis of largest spread.
void build(const std::vector<Vector3d>& p, std::vector<int>& order, std::vector<signed char>& axis, int begin,
           int end) {
  if (end - begin <= 1) {
    if (end - begin == 1) axis[begin] = 0;
    return;
  }
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = begin; i < end; ++i) lo = lo.cwiseMin(p[order[i]]), hi = hi.cwiseMax(p[order[i]]);
  int a = 0;
  (hi - lo).maxCoeff(&a);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](int i, int j) {
    return p[i][a] < p[j][a] || (p[i][a] == p[j][a] && i < j);
  });
  axis[mid] = static_cast<signed char>(a);
  build(p, order, axis, begin, mid);
  build(p, order, axis, mid + 1, end);
}

}  // namespace

ExampleNormals::ExampleNormals(const std::vector<Vector3d>& normals, const std::vector<double>& areas)
    : normals_(normals) {
  const int K = static_cast<int>(normals_.size());
  if (K == 0) throw std::invalid_argument("an example's Gauss map needs at least one normal");
  if (!areas.empty() && static_cast<int>(areas.size()) != K)
    throw std::invalid_argument("an example's Gauss map needs one area per normal");
  areas_ = areas.empty() ? std::vector<double>(K, 1.0) : areas;
  double total = 0;
  for (double a : areas_) {
    if (!std::isfinite(a) || a < 0) throw std::invalid_argument("an example's areas must be finite and >= 0");
    total += a;
  }
  if (!(total > 0) || !std::isfinite(total))
    throw std::invalid_argument("an example's areas must have a positive, finite sum");
  for (double& a : areas_) a /= total;

  order_.resize(K);
  std::iota(order_.begin(), order_.end(), 0);
  axis_.assign(K, 0);
  build(normals_, order_, axis_, 0, K);

  // Pull: the square root of the area density around each normal, relative to the densest. sqrt, not
  // pow: pow's glibc symbol is versioned 2.29, past what the module may need (cpp/python/glibc_baseline.cpp).
  const double chord = 2.0 * std::sin(0.5 * kDensityRadius);
  pull_.assign(K, 0.0);
  double densest = 0;
  for (int k = 0; k < K; ++k) {
    double sum = 0;
    within(normals_[k], chord, [&](int j) { sum += areas_[j]; });
    pull_[k] = sum;
    densest = std::max(densest, sum);
  }
  for (double& w : pull_) w = std::max(std::sqrt(w / densest), 1e-6);
}

template <class F>
void ExampleNormals::within(const Vector3d& x, double radius, F&& f) const {
  // Explicit stack of [begin, end) ranges: depth <= log2(K) + 1 < 64.
  int stack[2 * 64];
  int top = 0;
  stack[top++] = 0;
  stack[top++] = size();
  const double r2 = radius * radius;
  while (top > 0) {
    const int end = stack[--top], begin = stack[--top];
    if (begin >= end) continue;
    const int mid = begin + (end - begin) / 2, k = order_[mid], a = axis_[mid];
    if ((normals_[k] - x).squaredNorm() <= r2) f(k);
    const double d = x[a] - normals_[k][a];
    if (d - radius <= 0) stack[top++] = begin, stack[top++] = mid;
    if (d + radius >= 0) stack[top++] = mid + 1, stack[top++] = end;
  }
}

int ExampleNormals::nearest(const Vector3d& x) const {
  int best = 0;
  nearest(x, 1, &best);
  return best;
}

int ExampleNormals::nearest(const Vector3d& x_in, int count, int* index) const {
  const double len = x_in.norm();
  const Vector3d x = (len > 0 && std::isfinite(len)) ? Vector3d(x_in / len) : Vector3d::UnitZ();
  count = std::max(1, std::min({count, size(), kMaxNearest}));
  // The best `count` so far, nearest first (ties: lower index first); the last is the bound.
  double best_d2[kMaxNearest];
  int found = 0;
  const auto better = [&](double d2, int k, int j) { return d2 < best_d2[j] || (d2 == best_d2[j] && k < index[j]); };
  const auto bound = [&] { return found < count ? std::numeric_limits<double>::infinity() : best_d2[count - 1]; };
  // Explicit stack of ranges, each with the squared distance of its splitting plane (0: none).
  struct Range {
    int begin, end;
    double plane_d2;
  };
  Range stack[128];
  int top = 0;
  stack[top++] = {0, size(), 0.0};
  while (top > 0) {
    const Range r = stack[--top];
    if (r.begin >= r.end || r.plane_d2 > bound()) continue;
    const int mid = r.begin + (r.end - r.begin) / 2, k = order_[mid], a = axis_[mid];
    const double d2 = (normals_[k] - x).squaredNorm();
    if (found < count || better(d2, k, count - 1)) {
      int j = found < count ? found++ : count - 1;
      while (j > 0 && better(d2, k, j - 1)) {
        best_d2[j] = best_d2[j - 1];
        index[j] = index[j - 1];
        --j;
      }
      best_d2[j] = d2;
      index[j] = k;
    }
    const double d = x[a] - normals_[k][a];
    // The near side pushed last, so it is searched first; the far side is skipped when popped if the
    // plane is farther than the bound by then.
    if (d < 0) {
      stack[top++] = {mid + 1, r.end, d * d};
      stack[top++] = {r.begin, mid, 0.0};
    } else {
      stack[top++] = {r.begin, mid, d * d};
      stack[top++] = {mid + 1, r.end, 0.0};
    }
  }
  return found;
}

}  // namespace gauss
