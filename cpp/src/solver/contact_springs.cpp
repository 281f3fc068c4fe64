#include "gauss/solver/contact_springs.h"

#include <algorithm>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace gauss {

using Eigen::Vector3d;

void ContactSprings::clear() {
  for (int v : vertex_) slot_of_vertex_[v] = -1;
  vertex_.clear();
  unknown_.clear();
  anchor_.clear();
  idle_.clear();
  force_.clear();
  normal_.clear();
}

void ContactSprings::note_held(const std::vector<int>& held, const std::vector<Vector3d>& X,
                               const ConstrainedLaplacian& L, const MeshTopology& topo) {
  if (slot_of_vertex_.size() != X.size()) {
    clear();
    slot_of_vertex_.assign(X.size(), -1);
  }
  for (int& idle : idle_) ++idle;
  for (int v : held) {
    const int u = L.unknown_of_vertex(v);
    if (u < 0) continue;  // a pin or an anchor: the solve does not move it anyway
    int s = slot_of_vertex_[v];
    if (s < 0) {
      s = slot_of_vertex_[v] = static_cast<int>(vertex_.size());
      vertex_.push_back(v);
      unknown_.push_back(u);
      anchor_.emplace_back();
      idle_.push_back(0);
      force_.push_back(Vector3d::Zero());
      normal_.emplace_back();
    }
    anchor_[s] = X[v];
    // The vertex's normal (area-weighted) where the guard left it: a surface pressed onto another
    // meets it face to face, so this is the contact's normal, up to its sign.
    Vector3d n = Vector3d::Zero();
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const std::array<int, 3>& f = topo.faces[topo.vertex_corners[i] / 3];
      n += (X[f[1]] - X[f[0]]).cross(X[f[2]] - X[f[0]]);
    }
    const double length = n.norm();
    normal_[s] = length > 0 ? Vector3d(n / length) : Vector3d::Zero();
    idle_[s] = 0;
  }
  // Let go of the springs idle too long, keeping the others in their order (the sums below then
  // run in the same order on any thread count).
  size_t kept = 0;
  for (size_t s = 0; s < vertex_.size(); ++s) {
    if (idle_[s] > kKeepSteps) {
      slot_of_vertex_[vertex_[s]] = -1;
      continue;
    }
    vertex_[kept] = vertex_[s], unknown_[kept] = unknown_[s], anchor_[kept] = anchor_[s];
    idle_[kept] = idle_[s], force_[kept] = force_[s], normal_[kept] = normal_[s];
    slot_of_vertex_[vertex_[kept]] = static_cast<int>(kept);
    ++kept;
  }
  vertex_.resize(kept), unknown_.resize(kept), anchor_.resize(kept), idle_.resize(kept), force_.resize(kept);
  normal_.resize(kept);
}

void ContactSprings::solve(ConstrainedLaplacian& L, std::vector<Vector3d>& X) {
  const int k = count();
  const size_t n3 = 3 * static_cast<size_t>(L.num_unknowns());
  double* rhs = L.rhs_data();
  base_.assign(rhs, rhs + n3);
  L.solve_ordered_in_place(base_.data());  // L^-1 b
  const auto at = [&](const std::vector<double>& y, int s) {
    return Vector3d(&y[3 * static_cast<size_t>(L.position(unknown_[s]))]);
  };
  // The iterations read L^-1 P v at the springs' rows only: where the springs are a small part of
  // the mesh, a solve restricted to the elimination tree above them gives those rows for a part of a
  // whole solve's cost (cholesky_solver.h: on two threads where CholeskySolver::plan_splits); else
  // the whole solve.
  rows_.resize(k);
  for (int s = 0; s < k; ++s) rows_[s] = L.position(unknown_[s]);
  L.plan_sparse(rows_.data(), k, plan_);
  planned_ = kPlannedShare * static_cast<double>(L.factor_nonzeros()) > static_cast<double>(L.plan_nonzeros(plan_));
  // work_ := L^-1 P v for per-spring vectors v (right at the springs' rows).
  const auto apply_inverse = [&](const std::vector<Vector3d>& v) {
    work_.assign(n3, 0.0);
    for (int s = 0; s < k; ++s) {
      double* w = &work_[3 * static_cast<size_t>(rows_[s])];
      w[0] += v[s].x(), w[1] += v[s].y(), w[2] += v[s].z();
    }
    if (planned_) L.solve_planned_in_place(work_.data(), plan_);
    else L.solve_ordered_in_place(work_.data());
  };
  // A plane spring acts along its normal only: the system lives in the span of the normals, and
  // every vector of it is projected there.
  const auto project = [&](int s, const Vector3d& v) -> Vector3d { return normal_[s] * normal_[s].dot(v); };
  const auto weight = [&](int s) { return stiffness_ * L.diagonal(unknown_[s]); };
  // Preconditioner: 1 / w_i + 1 / L_ii, a guess at the diagonal of the system.
  const auto precondition = [&](int s, const Vector3d& r) { return r / (1.0 / weight(s) + 1.0 / L.diagonal(unknown_[s])); };
  target_.resize(k), residual_.resize(k), direction_.resize(k), preconditioned_.resize(k), applied_.resize(k);
  // The anchors are where the last solve's translation put them; the system is in the frame before it.
  double target_norm = 0;
  bool warm = false;
  for (int s = 0; s < k; ++s) {
    target_[s] = project(s, anchor_[s] - L.last_shift(vertex_[s]) - at(base_, s));
    target_norm += target_[s].squaredNorm();
    force_[s] = project(s, force_[s]);
    warm = warm || force_[s] != Vector3d::Zero();
  }
  // Residual of the warm start f: target - K^+ f - P^T L^-1 P f (projected). reached_: P^T L^-1 P f.
  reached_.assign(k, Vector3d::Zero());
  // Where every solve is a whole one, L^-1 (b + P f) is summed up from them as f is (in base_, which
  // holds L^-1 b), so that the step needs no final solve.
  const bool whole = !planned_;
  const auto add_to_base = [&](double scale) {
    for (size_t i = 0; i < n3; ++i) base_[i] += scale * work_[i];
  };
  if (warm) {
    apply_inverse(force_);
    for (int s = 0; s < k; ++s) reached_[s] = at(work_, s);
    if (whole) add_to_base(1.0);
  }
  double rz = 0, residual_norm = 0;
  for (int s = 0; s < k; ++s) {
    residual_[s] = target_[s] - force_[s] / weight(s) - project(s, reached_[s]);
    preconditioned_[s] = precondition(s, residual_[s]);
    direction_[s] = preconditioned_[s];
    rz += residual_[s].dot(preconditioned_[s]);
    residual_norm += residual_[s].squaredNorm();
  }
  const double stop = kTolerance * kTolerance * target_norm;
  iterations_ = 0;
  while (iterations_ < kMaxIterations && residual_norm > stop) {
    apply_inverse(direction_);
    double curvature = 0;
    for (int s = 0; s < k; ++s) {
      applied_[s] = direction_[s] / weight(s) + project(s, at(work_, s));
      curvature += direction_[s].dot(applied_[s]);
    }
    if (!(curvature > 0)) break;
    const double alpha = rz / curvature;
    for (int s = 0; s < k; ++s) reached_[s] += alpha * at(work_, s);
    if (whole) add_to_base(alpha);
    double next_rz = 0;
    residual_norm = 0;
    for (int s = 0; s < k; ++s) {
      force_[s] += alpha * direction_[s];
      residual_[s] -= alpha * applied_[s];
      preconditioned_[s] = precondition(s, residual_[s]);
      next_rz += residual_[s].dot(preconditioned_[s]);
      residual_norm += residual_[s].squaredNorm();
    }
    const double beta = next_rz / rz;
    rz = next_rz;
    for (int s = 0; s < k; ++s) direction_[s] = preconditioned_[s] + beta * direction_[s];
    ++iterations_;
  }
  // x = L^-1 (b + P f): summed up already, or the springs' forces on the right-hand side, one whole solve.
  if (whole) {
    std::copy(base_.begin(), base_.end(), rhs);
  } else {
    for (int s = 0; s < k; ++s) {
      double* r = rhs + 3 * static_cast<size_t>(rows_[s]);
      r[0] += force_[s].x(), r[1] += force_[s].y(), r[2] += force_[s].z();
    }
    L.solve_ordered_in_place(rhs);
  }
  L.finish_solve(X);
}

}  // namespace gauss
