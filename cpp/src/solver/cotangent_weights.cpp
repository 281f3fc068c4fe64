#include "gauss/solver/cotangent_weights.h"

#include <Eigen/Geometry>
#include <cmath>

namespace gauss {

TriangleWeights cotangent_weights(const Eigen::Vector3d e[3]) {
  TriangleWeights out{{kIllShapedWeight, kIllShapedWeight, kIllShapedWeight}, false};
  const double twice_area = e[0].cross(e[1]).norm();
  std::array<double, 3> cot;
  for (int k = 0; k < 3; ++k) {
    // Slot k's opposite corner is (k+2)%3; its angle lies between -e[(k+2)%3] and e[(k+1)%3].
    const double c = -e[(k + 2) % 3].dot(e[(k + 1) % 3]) / twice_area;
    if (!(std::abs(c) <= kMaxCotangent)) return out;  // also zero area (inf, NaN) and overflow
    cot[k] = c;
  }
  for (int k = 0; k < 3; ++k) out.w[k] = 0.5 * cot[k];
  out.well_shaped = true;
  return out;
}

int floor_negative_edge_weights(const MeshTopology& topo, std::vector<std::array<double, 3>>& slot_weight,
                                std::vector<double>& edge_weight) {
  int changed = 0;
  for (size_t e = 0; e < edge_weight.size(); ++e) {
    if (!(edge_weight[e] < kMinEdgeWeight)) continue;
    const int begin = topo.edge_slot_start[e], end = topo.edge_slot_start[e + 1];
    for (int i = begin; i < end; ++i) slot_weight[topo.edge_slots[i] / 3][topo.edge_slots[i] % 3] = kIllShapedWeight / (end - begin);
    edge_weight[e] = kIllShapedWeight;
    ++changed;
  }
  return changed;
}

}  // namespace gauss
