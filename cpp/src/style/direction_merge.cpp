#include "gauss/style/direction_merge.h"
#include "gauss/util/constants.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace gauss {
namespace {

using Eigen::Vector3d;

bool lexicographic_less(const Vector3d& a, const Vector3d& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// Grid keys: 21 bits per axis, so cells must be at least 2 / 2^21 wide (kMinMergeAngle's chord).
constexpr int kKeyBits = 21;
constexpr int64_t kKeyMax = (int64_t(1) << kKeyBits) - 1;

int64_t cell_coordinate(double x, double cell) {
  return std::clamp(static_cast<int64_t>(std::floor((x + 1.0) / cell)), int64_t(0), kKeyMax);
}

int64_t cell_key(int64_t cx, int64_t cy, int64_t cz) { return cx | (cy << kKeyBits) | (cz << (2 * kKeyBits)); }

// "Next unclaimed position at or after p" with path halving: skipping claimed inputs keeps every
// scan proportional to the unclaimed inputs near a seed.
int next_free(std::vector<int>& next, int p) {
  while (next[p] != p) {
    next[p] = next[next[p]];
    p = next[p];
  }
  return p;
}

}  // namespace

MergedDirections merge_directions(const std::vector<Vector3d>& D, const std::vector<double>& weights,
                                  double max_angle) {
  std::vector<int> all(D.size());
  std::iota(all.begin(), all.end(), 0);
  return merge_directions(D, weights, all, max_angle);
}

MergedDirections merge_directions(const std::vector<Vector3d>& D, const std::vector<double>& weights,
                                  const std::vector<int>& subset, double max_angle) {
  if (!(max_angle >= 0.0 && max_angle <= kPi / 2))
    throw std::invalid_argument("the merge angle must lie between 0 and 90 degrees");
  if (!weights.empty() && weights.size() != D.size())
    throw std::invalid_argument("merge weights must have one entry per direction");
  for (int i : subset) {
    if (i < 0 || i >= static_cast<int>(D.size())) throw std::invalid_argument("merge subset index out of range");
    if (!D[i].allFinite() || std::abs(D[i].squaredNorm() - 1.0) > 1e-6)
      throw std::invalid_argument("directions to merge must be finite unit vectors");
    if (!weights.empty() && !(weights[i] >= 0.0 && std::isfinite(weights[i]))) {
      std::ostringstream msg;
      msg << "merge weights must be finite and >= 0 (weight " << i << " is " << weights[i] << ")";
      throw std::invalid_argument(msg.str());
    }
  }
  auto weight = [&](int i) { return weights.empty() ? 1.0 : weights[i]; };
  auto seed_before = [&](int a, int b) {
    if (weight(a) != weight(b)) return weight(a) > weight(b);
    return lexicographic_less(D[a], D[b]);
  };
  // Within a cell, members are claimed in direction order, so the sums below do not depend on the
  // input order either.
  auto cell_order = [&](int a, int b) { return lexicographic_less(D[a], D[b]) || (D[a] == D[b] && seed_before(a, b)); };

  const int n = static_cast<int>(subset.size());
  const bool identical_only = max_angle < kMinMergeAngle;
  const double cell = identical_only ? 2.0 / kKeyMax : 2.0 * std::sin(0.5 * max_angle);
  const double min_dot = std::cos(max_angle);
  std::vector<int64_t> key_of(D.size(), 0);
  std::vector<int> by_cell(subset);
  for (int i : subset)
    key_of[i] = cell_key(cell_coordinate(D[i].x(), cell), cell_coordinate(D[i].y(), cell),
                         cell_coordinate(D[i].z(), cell));
  std::sort(by_cell.begin(), by_cell.end(), [&](int a, int b) {
    return key_of[a] != key_of[b] ? key_of[a] < key_of[b] : cell_order(a, b);
  });
  std::vector<int64_t> keys(n);
  for (int p = 0; p < n; ++p) keys[p] = key_of[by_cell[p]];
  std::vector<int> position(D.size(), -1);
  for (int p = 0; p < n; ++p) position[by_cell[p]] = p;
  std::vector<int> next(n + 1);
  std::iota(next.begin(), next.end(), 0);
  auto claim = [&](int p) { next[p] = p + 1; };

  std::vector<int> order(subset);
  std::sort(order.begin(), order.end(), seed_before);
  MergedDirections out;
  std::vector<int> cluster_at(n, -1);  // by position in by_cell
  std::vector<Vector3d> sums;
  for (int seed : order) {
    const int sp = position[seed];
    if (cluster_at[sp] >= 0) continue;
    const int c = static_cast<int>(out.weights.size());
    Vector3d sum = Vector3d::Zero();
    double total = 0.0;
    auto take = [&](int p) {
      const int j = by_cell[p];
      cluster_at[p] = c;
      claim(p);
      sum += weight(j) * D[j];
      total += weight(j);
    };
    take(sp);  // first, whatever rounding says about its distance to itself
    if (identical_only) {
      // Identical directions are adjacent in by_cell (same cell, direction order).
      int lo = sp, hi = sp;
      while (lo > 0 && D[by_cell[lo - 1]] == D[seed]) --lo;
      while (hi + 1 < n && D[by_cell[hi + 1]] == D[seed]) ++hi;
      for (int p = next_free(next, lo); p <= hi; p = next_free(next, p)) take(p);
    } else {
      const int64_t cx = key_of[seed] & kKeyMax, cy = (key_of[seed] >> kKeyBits) & kKeyMax,
                    cz = key_of[seed] >> (2 * kKeyBits);
      for (int64_t z = std::max<int64_t>(cz - 1, 0); z <= std::min(cz + 1, kKeyMax); ++z)
        for (int64_t y = std::max<int64_t>(cy - 1, 0); y <= std::min(cy + 1, kKeyMax); ++y) {
          // The three cells along x have consecutive keys: one range.
          const int64_t first = cell_key(std::max<int64_t>(cx - 1, 0), y, z), last = cell_key(std::min(cx + 1, kKeyMax), y, z);
          const int lo = static_cast<int>(std::lower_bound(keys.begin(), keys.end(), first) - keys.begin());
          const int hi = static_cast<int>(std::upper_bound(keys.begin(), keys.end(), last) - keys.begin());
          for (int p = next_free(next, lo); p < hi; p = next_free(next, p + 1))
            if (D[by_cell[p]].dot(D[seed]) >= min_dot) take(p);
        }
    }
    const double len = sum.norm();
    out.directions.push_back(total > 0.0 && len > 1e-300 ? Vector3d(sum / len) : D[seed]);
    out.weights.push_back(total);
  }
  out.cluster_of.resize(n);
  for (int i = 0; i < n; ++i) out.cluster_of[i] = cluster_at[position[subset[i]]];
  return out;
}

}  // namespace gauss
