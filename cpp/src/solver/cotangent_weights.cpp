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

}  // namespace gauss
