#include "gauss/solver/constrained_laplacian.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <stdexcept>

#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Vector3d;

namespace {

// The lower triangle of L_ff (n by n), built column by column from the edge list (sorted by (lo, hi),
// and the numbering of unknowns follows the vertices'). unknown_of_vertex: #V, -1 for fixed vertices.
Eigen::SparseMatrix<double> free_block(const MeshTopology& topo, const std::vector<double>& edge_weight,
                                       const std::vector<int>& unknown_of_vertex, int n) {
  std::vector<double> diagonal(n, 0.0);
  std::vector<int> col_count(n, 1);  // the diagonal
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const int ua = unknown_of_vertex[topo.edges[e][0]], ub = unknown_of_vertex[topo.edges[e][1]];
    const double w = edge_weight[e];
    if (ua >= 0) diagonal[ua] += w;
    if (ub >= 0) diagonal[ub] += w;
    if (ua >= 0 && ub >= 0) ++col_count[ua];  // ua < ub: entry (ub, ua) in column ua
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.reserve(col_count);
  for (int u = 0; u < n; ++u) A.insert(u, u) = diagonal[u];
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const int ua = unknown_of_vertex[topo.edges[e][0]], ub = unknown_of_vertex[topo.edges[e][1]];
    if (ua >= 0 && ub >= 0) A.insert(ub, ua) = -edge_weight[e];
  }
  A.makeCompressed();
  return A;
}

}  // namespace

ConstrainedLaplacian::ConstrainedLaplacian(const MeshTopology& topo, const std::vector<double>& edge_weight,
                                           const std::vector<Vector3d>& rest, const std::vector<int64_t>& pinned,
                                           const std::vector<Vector3d>& pin_positions, Progress* progress) {
  const int nV = topo.num_vertices;
  const int nC = topo.num_components;
  if (pin_positions.size() != pinned.size() || edge_weight.size() != topo.edges.size() ||
      rest.size() != static_cast<size_t>(nV))
    throw std::invalid_argument("ConstrainedLaplacian: the sizes of the mesh, weights, rest positions and pins disagree");

  // Fixed vertices: the pins, then the first vertex of every component without a pin (its anchor).
  // The per-vertex scratch lives in this block only: the factorization below is the set-up's peak.
  num_pins_ = static_cast<int>(pinned.size());
  pinned_.assign(pinned.begin(), pinned.end());
  fixed_position_ = pin_positions;
  Eigen::SparseMatrix<double> A;
  {
    std::vector<int> fixed_index(nV, -1);
    std::vector<uint8_t> has_pin(nC, 0);
    for (int i = 0; i < num_pins_; ++i) {
      fixed_index[pinned_[i]] = i;
      if (topo.component[pinned_[i]] >= 0) has_pin[topo.component[pinned_[i]]] = 1;
    }
    component_rest_center_.assign(nC, Vector3d::Zero());
    component_size_.assign(nC, 0);
    component_shift_.assign(nC, Vector3d::Zero());
    free_component_.assign(nV, -1);
    std::vector<uint8_t> anchored(nC, 0);
    for (int v = 0; v < nV; ++v) {
      const int c = topo.component[v];
      if (c < 0) continue;
      component_rest_center_[c] += rest[v];
      ++component_size_[c];
      if (has_pin[c]) continue;
      free_component_[v] = c;
      if (!anchored[c]) {
        anchored[c] = 1;
        fixed_index[v] = static_cast<int>(fixed_position_.size());
        fixed_position_.push_back(rest[v]);
        anchor_vertex_.push_back(v);
      }
    }
    for (int c = 0; c < nC; ++c) component_rest_center_[c] /= component_size_[c];

    // Unknowns: the other referenced vertices, numbered in vertex order.
    std::vector<int>& unknown_of_vertex = unknown_of_vertex_;
    unknown_of_vertex.assign(nV, -1);
    for (int v = 0; v < nV; ++v)
      if (topo.component[v] >= 0 && fixed_index[v] < 0) {
        unknown_of_vertex[v] = static_cast<int>(vertex_of_unknown_.size());
        vertex_of_unknown_.push_back(v);
      }
    diagonal_.assign(vertex_of_unknown_.size(), 0.0);
    for (size_t e = 0; e < topo.edges.size(); ++e)
      for (int v : topo.edges[e])
        if (unknown_of_vertex[v] >= 0) diagonal_[unknown_of_vertex[v]] += edge_weight[e];
    // Edges between an unknown and a fixed vertex become couplings, in edge order.
    for (size_t e = 0; e < topo.edges.size(); ++e) {
      const int a = topo.edges[e][0], b = topo.edges[e][1];
      const int ua = unknown_of_vertex[a], ub = unknown_of_vertex[b];
      if (ua >= 0 && ub < 0) couplings_.push_back({ua, fixed_index[b], edge_weight[e]});
      else if (ub >= 0 && ua < 0) couplings_.push_back({ub, fixed_index[a], edge_weight[e]});
    }
    if (num_unknowns() > 0) A = free_block(topo, edge_weight, unknown_of_vertex, num_unknowns());
  }
  const int n = num_unknowns();
  if (n > 0) cholesky_.factor(std::move(A), progress);
  constant_rhs_.resize(n);
  update_constant_rhs();
  rhs_.assign(3 * static_cast<size_t>(n), 0.0);
}

void ConstrainedLaplacian::update_constant_rhs() {
  std::fill(constant_rhs_.begin(), constant_rhs_.end(), Vector3d::Zero());
  for (const Coupling& c : couplings_) constant_rhs_[c.unknown] += c.weight * fixed_position_[c.fixed];
}

void ConstrainedLaplacian::set_pin_positions(const std::vector<Vector3d>& pin_positions) {
  if (pin_positions.size() != static_cast<size_t>(num_pins_))
    throw std::invalid_argument("ConstrainedLaplacian: one position per pin is needed");
  std::copy(pin_positions.begin(), pin_positions.end(), fixed_position_.begin());
  update_constant_rhs();
}

void ConstrainedLaplacian::place_pins(std::vector<Vector3d>& X) const {
  for (int i = 0; i < num_pins_; ++i) X[pinned_[i]] = fixed_position_[i];
}

void ConstrainedLaplacian::solve(std::vector<Vector3d>& X) {
  if (num_unknowns() > 0) cholesky_.solve_ordered_in_place(rhs_.data());
  finish_solve(X);
}

void ConstrainedLaplacian::finish_solve(std::vector<Vector3d>& X) {
  const int n = num_unknowns();
  parallel::for_each(n, parallel::kMinParallelItems, [&](int u) {
    X[vertex_of_unknown_[u]] = Vector3d(&rhs_[3 * static_cast<size_t>(cholesky_.position(u))]);
  });
  // Anchors went into the solve at their rest positions; translate each free component so that its
  // centroid stays where the rest pose had it.
  for (size_t a = 0; a < anchor_vertex_.size(); ++a) X[anchor_vertex_[a]] = fixed_position_[num_pins_ + a];
  std::fill(component_shift_.begin(), component_shift_.end(), Vector3d::Zero());
  const int nV = static_cast<int>(free_component_.size());
  for (int v = 0; v < nV; ++v)
    if (free_component_[v] >= 0) component_shift_[free_component_[v]] += X[v];
  for (size_t c = 0; c < component_shift_.size(); ++c)
    component_shift_[c] = component_rest_center_[c] - component_shift_[c] / component_size_[c];
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    if (free_component_[v] >= 0) X[v] += component_shift_[free_component_[v]];
  });
}

}  // namespace gauss
