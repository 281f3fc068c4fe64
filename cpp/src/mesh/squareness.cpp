#include "gauss/mesh/squareness.h"
#include "gauss/util/constants.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gauss {

double squareness(const double* V, const int64_t* F, int num_faces, const Eigen::Vector3d& up, double degrees) {
  const double cos_limit = std::cos(degrees * kPi / 180.0);
  const Eigen::Vector3d a = std::abs(up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (a - a.dot(up) * up).normalized(), e2 = up.cross(e1);
  double area = 0;
  std::vector<Eigen::Vector2d> points;
  for (int f = 0; f < num_faces; ++f) {
    const Eigen::Vector3d p[3] = {Eigen::Vector3d(V + 3 * F[3 * f]), Eigen::Vector3d(V + 3 * F[3 * f + 1]),
                                  Eigen::Vector3d(V + 3 * F[3 * f + 2])};
    const Eigen::Vector3d c = (p[1] - p[0]).cross(p[2] - p[0]);
    const double len = c.norm();
    if (!(len > 0) || !std::isfinite(len) || c.dot(up) < cos_limit * len) continue;
    area += 0.5 * len;
    for (const auto& q : p) points.emplace_back(q.dot(e1), q.dot(e2));
  }
  if (points.empty()) return 0.0;
  // The smallest square over orientations a tenth of a degree apart (a quarter turn repeats).
  double side = INFINITY;
  for (int i = 0; i < 900; ++i) {
    const double t = i * 0.1 * kPi / 180.0;
    const Eigen::Vector2d x(std::cos(t), std::sin(t)), y(-std::sin(t), std::cos(t));
    double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    for (const auto& q : points) {
      const double qx = q.dot(x), qy = q.dot(y);
      lo_x = std::min(lo_x, qx), hi_x = std::max(hi_x, qx), lo_y = std::min(lo_y, qy), hi_y = std::max(hi_y, qy);
    }
    side = std::min(side, std::max(hi_x - lo_x, hi_y - lo_y));
  }
  return side > 0 ? area / (side * side) : 0.0;
}

}  // namespace gauss
