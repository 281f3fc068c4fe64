#include "gauss/fixed_point_iteration.h"

#include <algorithm>

namespace gauss {

double relative_change(const std::vector<Eigen::Vector3d>& previous, const std::vector<Eigen::Vector3d>& current,
                       const std::vector<Eigen::Vector3d>& rest, double size) {
  // Maxima do not depend on the order they are taken in: serial is as deterministic as it is cheap
  // (two passes over #V, ~1% of a step).
  double change = 0.0, displacement = 0.0;
  const size_t n = current.size();
  for (size_t v = 0; v < n; ++v) {
    change = std::max(change, (current[v] - previous[v]).cwiseAbs().maxCoeff());
    displacement = std::max(displacement, (current[v] - rest[v]).cwiseAbs().maxCoeff());
  }
  if (change == 0.0) return 0.0;
  displacement = std::max(displacement, kStillDisplacement * size);
  return change / displacement;
}

}  // namespace gauss
