#include "gauss/mesh/flat_vertex_share.h"
#include "gauss/util/constants.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace gauss {

double flat_vertex_share(const double* V, int num_vertices, const int64_t* F, int num_faces, double max_defect) {
  const double kTwoPi = 2.0 * kPi;
  std::vector<double> angle_sum(num_vertices, 0.0);
  std::vector<char> used(num_vertices, 0), boundary(num_vertices, 0);
  std::vector<std::pair<int64_t, int64_t>> edges;  // undirected, one per face side
  edges.reserve(3 * static_cast<size_t>(num_faces));
  for (int f = 0; f < num_faces; ++f) {
    const int64_t* t = F + 3 * static_cast<int64_t>(f);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const int64_t i = t[k], j = t[(k + 1) % 3], l = t[(k + 2) % 3];
      const Eigen::Vector3d p(V + 3 * i), a = Eigen::Vector3d(V + 3 * j) - p, b = Eigen::Vector3d(V + 3 * l) - p;
      // atan2 of |a x b| and a.b: accurate for angles near 0 and pi alike.
      angle_sum[i] += std::atan2(a.cross(b).norm(), a.dot(b));
      used[i] = 1;
      edges.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size();) {
    size_t end = e;
    while (end < edges.size() && edges[end] == edges[e]) ++end;
    if (end - e == 1) boundary[edges[e].first] = boundary[edges[e].second] = 1;
    e = end;
  }
  int counted = 0, flat = 0;
  for (int v = 0; v < num_vertices; ++v) {
    if (!used[v] || boundary[v]) continue;
    ++counted;
    if (std::abs(kTwoPi - angle_sum[v]) < max_defect) ++flat;
  }
  return counted > 0 ? static_cast<double>(flat) / counted : 0.0;
}

}  // namespace gauss
