// GaussSolver's read-outs: the current vertices in the caller's numbering and frame, and the energies.
// Not on a step's path: the energies recompute what they need.
#include <algorithm>

#include <Eigen/Dense>

#include "gauss/solver/closest_rotation.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Matrix3d;
using Eigen::Vector3d;

template <typename T>
void GaussSolver::write_vertices(T* out) const {
  const int nV = topo_.num_vertices;
  for (int old = 0; old < nV; ++old) {
    const int v = new_of_old_[old];
    const Vector3d p = topo_.component[v] >= 0 ? to_caller(X_[v]) : input_[v];
    out[3 * old] = static_cast<T>(p.x());
    out[3 * old + 1] = static_cast<T>(p.y());
    out[3 * old + 2] = static_cast<T>(p.z());
  }
  // Pins are returned exactly as given, not through the normalization round trip; but for a pin the
  // self-intersection guard holds short of its target (where X_ is not the target's image).
  for (size_t i = 0; i < pinned_input_.size(); ++i) {
    if (guard_ && X_[new_of_old_[pinned_input_[i]]] != Vector3d((pin_targets_[i] - center_) / scale_)) continue;
    for (int k = 0; k < 3; ++k) out[3 * pinned_input_[i] + k] = static_cast<T>(pin_targets_[i][k]);
  }
}

std::vector<int> GaussSolver::held_vertex_indices() const {
  std::vector<int> found;
  if (!guard_ || guard_->last_held() == 0) return found;
  // A live run reads this after every step the guard holds: the inverse numbering is made once, so a
  // call costs the held vertices, not the mesh.
  if (old_of_new_.size() != new_of_old_.size()) {
    old_of_new_.resize(new_of_old_.size());
    for (size_t old = 0; old < new_of_old_.size(); ++old) old_of_new_[new_of_old_[old]] = static_cast<int>(old);
  }
  found.reserve(guard_->last_held_vertices().size());
  for (int v : guard_->last_held_vertices()) found.push_back(old_of_new_[v]);
  std::sort(found.begin(), found.end());
  return found;
}

void GaussSolver::copy_vertices(double* out) const { write_vertices(out); }
void GaussSolver::copy_vertices(float* out) const { write_vertices(out); }

double GaussSolver::arap_energy() const {
  // E_ARAP (Eqs. 1-2) with spokes-and-rims neighbourhoods and each vertex's optimal rotation for the
  // current mesh. A read-out, not on the step's path: it recomputes what it needs.
  const int nV = topo_.num_vertices;
  std::vector<double> per_vertex(nV, 0.0);
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    const int begin = topo_.vertex_corner_start[v], end = topo_.vertex_corner_start[v + 1];
    if (begin == end) return;
    Matrix3d M = Matrix3d::Zero();
    for (int i = begin; i < end; ++i) {
      const int f = topo_.vertex_corners[i] / 3;
      const auto& t = topo_.faces[f];
      for (int k = 0; k < 3; ++k) M += (X_[t[(k + 1) % 3]] - X_[t[k]]) * slot_rest(f, k).transpose();
    }
    const Matrix3d R = closest_rotation(M);
    double sum = 0;
    for (int i = begin; i < end; ++i) {
      const int f = topo_.vertex_corners[i] / 3;
      const auto& t = topo_.faces[f];
      for (int k = 0; k < 3; ++k) {
        const Vector3d e = X_[t[(k + 1) % 3]] - X_[t[k]];
        const Vector3d eh = rest_[t[(k + 1) % 3]] - rest_[t[k]];
        sum += 0.5 * slot_weight_[f][k] * (e - R * eh).squaredNorm();
      }
    }
    per_vertex[v] = sum;
  });
  double total = 0;  // sequential sum: identical for any thread count
  for (double e : per_vertex) total += e;
  return total;
}

double GaussSolver::g_energy() const {
  update_preferred_normals();  // a developable or gauss_map style's g is centred on the current mesh's preferred normals
  double total = 0;
  for (size_t f = 0; f < topo_.faces.size(); ++f) {
    const int s = face_style_[f];
    if (s == -1) continue;
    const auto& t = topo_.faces[f];
    const Vector3d c = (X_[t[1]] - X_[t[0]]).cross(X_[t[2]] - X_[t[0]]);
    const double len = c.norm();
    if (!(len > 0) || !std::isfinite(len)) continue;
    const Vector3d n = c / len;
    const Vector3d& p = any_anchored_ ? preferred_normal_[f] : n;
    const auto value = [&](const PreferenceFunction& g) {
      double v;
      Vector3d grad;
      Eigen::Matrix3d hess;
      g.evaluate(n, p, v, grad, hess);
      return v;
    };
    if (s >= 0) {
      total += face_weight_[f] * value(styles_[s]);
    } else {
      for (int k = blend_start_[-2 - s]; k < blend_start_[-1 - s]; ++k)
        total += blend_terms_[k].weight * value(styles_[blend_terms_[k].style]);
    }
  }
  return total;
}

}  // namespace gauss
