#include "gauss/solver/developable_normals.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void developable_normals(const MeshTopology& topo, const std::vector<Vector3d>& X, std::vector<Matrix3d>& moment,
                         std::vector<Vector3d>& ruling, std::vector<Vector3d>& preferred) {
  const int nF = static_cast<int>(topo.faces.size()), nV = topo.num_vertices;
  // preferred holds each face's cross product (twice its area times its normal) until the last pass.
  parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
    const auto& t = topo.faces[f];
    preferred[f] = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
  });
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    Matrix3d M = Matrix3d::Zero();
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const Vector3d& c = preferred[topo.vertex_corners[i] / 3];
      const double len = c.norm();
      if (len > 0 && std::isfinite(len)) M.noalias() += (c / len) * c.transpose();
    }
    moment[v] = M;
  });
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    Matrix3d M = Matrix3d::Zero();
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const auto& t = topo.faces[topo.vertex_corners[i] / 3];
      M += moment[t[0]] + moment[t[1]] + moment[t[2]];
    }
    const double trace = M.trace();
    if (!(trace > 0) || !std::isfinite(trace)) {
      ruling[v] = Vector3d::Zero();  // no face of non-zero area: no pull
      return;
    }
    Eigen::SelfAdjointEigenSolver<Matrix3d> eig;
    eig.computeDirect(M / trace);  // scaled to trace 1: computeDirect wants no huge entries
    ruling[v] = eig.eigenvectors().col(0);  // eigenvalues ascend
  });
  parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
    const auto& t = topo.faces[f];
    const Vector3d c = preferred[f];
    const double len = c.norm();
    if (!(len > 0) || !std::isfinite(len)) {
      preferred[f] = Vector3d::UnitZ();
      return;
    }
    const Vector3d n = c / len;
    Vector3d p = Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vector3d& a = ruling[t[k]];
      p += n - n.dot(a) * a;
    }
    const double plen = p.norm();
    preferred[f] = (plen > 1e-6 && std::isfinite(plen)) ? Vector3d(p / plen) : n;
  });
}

}  // namespace gauss
