#include "gauss/mesh/alignment_share.h"
#include "gauss/util/constants.h"

#include <Eigen/Geometry>
#include <cmath>

namespace gauss {

double alignment_share(const double* V, const int64_t* F, int num_faces,
                       const std::vector<Eigen::Vector3d>& normals, double max_degrees) {
  const double cos_max = std::cos(max_degrees * kPi / 180.0);
  double aligned = 0, total = 0;
  for (int f = 0; f < num_faces; ++f) {
    const Eigen::Vector3d a(V + 3 * F[3 * f]), b(V + 3 * F[3 * f + 1]), c(V + 3 * F[3 * f + 2]);
    const Eigen::Vector3d cr = (b - a).cross(c - a);
    const double twice_area = cr.norm();
    if (!(twice_area > 0)) continue;
    total += twice_area;
    const Eigen::Vector3d n = cr / twice_area;
    for (const Eigen::Vector3d& p : normals)
      if (n.dot(p) >= cos_max) {
        aligned += twice_area;
        break;
      }
  }
  return total > 0 ? aligned / total : 0.0;
}

}  // namespace gauss
