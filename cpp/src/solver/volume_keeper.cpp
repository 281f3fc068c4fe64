#include "gauss/solver/volume_keeper.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gauss {

using Eigen::Vector3d;

VolumeKeeper::VolumeKeeper(const MeshTopology& topo, const std::vector<Vector3d>& rest,
                           const std::vector<int64_t>& pinned) {
  const int nC = topo.num_components;
  closed_.assign(nC, 1);
  centroid_.assign(nC, Vector3d::Zero());
  count_.assign(nC, 0);
  size_.assign(nC, 0.0);
  factor_.assign(nC, 1.0);
  for (size_t e = 0; e + 1 < topo.edge_slot_start.size(); ++e)
    if (topo.edge_slot_start[e + 1] - topo.edge_slot_start[e] == 1) {
      const int f = topo.edge_slots[topo.edge_slot_start[e]] / 3;
      closed_[topo.component[topo.faces[f][0]]] = 0;
    }
  measure(topo, rest);
  rest_size_ = size_;
  // Degenerate rest sizes, against each component's extent.
  std::vector<Vector3d> lo(nC, Vector3d::Constant(INFINITY)), hi(nC, Vector3d::Constant(-INFINITY));
  for (int v = 0; v < topo.num_vertices; ++v) {
    const int c = topo.component[v];
    if (c < 0) continue;
    lo[c] = lo[c].cwiseMin(rest[v]);
    hi[c] = hi[c].cwiseMax(rest[v]);
  }
  for (int c = 0; c < nC; ++c) {
    const double extent = (hi[c] - lo[c]).maxCoeff();
    const double unit = closed_[c] ? extent * extent * extent : extent * extent;
    if (!(std::abs(rest_size_[c]) > kDegenerate * unit)) rest_size_[c] = 0.0;
  }
  for (int64_t v : pinned)
    if (topo.component[v] >= 0) rest_size_[topo.component[v]] = 0.0;
  for (int c = 0; c < nC; ++c)
    if (rest_size_[c] != 0.0) {
      ++num_kept_;
      num_closed_ += closed_[c];
    }
}

void VolumeKeeper::measure(const MeshTopology& topo, const std::vector<Vector3d>& X) {
  // Serial sums in a fixed order: the same result for any thread count (a pass over #F, cheap:
  // docs/performance.md#figures-behind-the-codes-choices).
  std::fill(centroid_.begin(), centroid_.end(), Vector3d::Zero());
  std::fill(count_.begin(), count_.end(), 0);
  std::fill(size_.begin(), size_.end(), 0.0);
  for (int v = 0; v < topo.num_vertices; ++v) {
    const int c = topo.component[v];
    if (c < 0) continue;
    centroid_[c] += X[v];
    ++count_[c];
  }
  for (size_t c = 0; c < centroid_.size(); ++c) centroid_[c] /= count_[c];
  for (const auto& t : topo.faces) {
    const int c = topo.component[t[0]];
    const Vector3d a = X[t[0]] - centroid_[c], b = X[t[1]] - centroid_[c], d = X[t[2]] - centroid_[c];
    size_[c] += closed_[c] ? a.dot(b.cross(d)) / 6.0 : 0.5 * (b - a).cross(d - a).norm();
  }
}

void VolumeKeeper::restore(const MeshTopology& topo, std::vector<Vector3d>& X) {
  if (num_kept_ == 0) return;
  measure(topo, X);
  for (size_t c = 0; c < size_.size(); ++c) {
    factor_[c] = 1.0;
    if (rest_size_[c] == 0.0) continue;
    const double ratio = rest_size_[c] / size_[c];  // negative: turned inside out
    if (!(ratio >= 1.0 / kMaxRatio && ratio <= kMaxRatio)) continue;
    factor_[c] = closed_[c] ? std::cbrt(ratio) : std::sqrt(ratio);
  }
  for (int v = 0; v < topo.num_vertices; ++v) {
    const int c = topo.component[v];
    if (c >= 0 && factor_[c] != 1.0) X[v] = centroid_[c] + factor_[c] * (X[v] - centroid_[c]);
  }
}

}  // namespace gauss
