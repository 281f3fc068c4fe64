#include "gauss/mesh/developability.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace gauss {

double developability(const double* V, int num_vertices, const int64_t* F, int num_faces) {
  std::vector<Eigen::Matrix3d> moment(num_vertices, Eigen::Matrix3d::Zero());
  std::vector<double> area(num_vertices, 0.0);
  for (int f = 0; f < num_faces; ++f) {
    const Eigen::Vector3d a(V + 3 * F[3 * f]), b(V + 3 * F[3 * f + 1]), c(V + 3 * F[3 * f + 2]);
    const Eigen::Vector3d cr = (b - a).cross(c - a);
    const double twice_area = cr.norm();
    if (!(twice_area > 0) || !std::isfinite(twice_area)) continue;
    const Eigen::Matrix3d nn = (cr / twice_area) * (cr / twice_area).transpose();
    for (int k = 0; k < 3; ++k) {
      const int64_t v = F[3 * f + k];
      moment[v] += twice_area * nn;
      area[v] += twice_area;
    }
  }
  double sum = 0;
  int counted = 0;
  for (int v = 0; v < num_vertices; ++v) {
    if (!(area[v] > 0)) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(moment[v] / area[v], Eigen::EigenvaluesOnly);
    sum += std::max(0.0, eig.eigenvalues()(0));
    ++counted;
  }
  return counted > 0 ? sum / counted : 0.0;
}

}  // namespace gauss
