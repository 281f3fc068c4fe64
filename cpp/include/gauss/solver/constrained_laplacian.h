#pragma once
// The global step of Algorithm 1 as a linear system: the cotangent Laplacian of Eq. 27 with positional
// constraints (the paper's section 3.3: "constraints on vertex positions can be integrated similarly
// to ARAP").
//
// Fixed vertices are the pins plus one anchor per connected component without a pin: ARAP determines
// such a component only up to a translation, the anchor removes that null space, and after each solve
// the component is translated back onto its rest centroid. The free vertices are the unknowns; their
// block L_ff is factored once, in the constructor. The fixed neighbours' part, -L_fp x_p, is a constant
// right-hand side: set_pin_positions() recomputes it without re-factoring. Lambda never enters the
// matrix (Eq. 27 divides the right-hand side by 1 + lambda), so only a new set of pins re-factors.
//
// Usage (all positions in the solver's normalized frame, vertices in its numbering):
//   ConstrainedLaplacian L(topo, edge_weight, rest, pinned, pin_positions);  // the expensive part
//   L.place_pins(X);
//   per step:
//     for each unknown u (in parallel):  L.set_rhs(u, L.constant_rhs(u) + b_u);
//     L.solve(X);                        // no allocation
// where b_u is Eq. 27's right-hand side (without the fixed neighbours) at vertex L.vertex_of_unknown(u).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gauss/sparse/cholesky_solver.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/util/progress.h"

namespace gauss {

class ConstrainedLaplacian {
 public:
  // An empty system (no unknowns); assign a constructed one before use.
  ConstrainedLaplacian() = default;

  // topo         the mesh (edges #E by 2 with lo < hi, component #V: -1 for an unreferenced vertex)
  // edge_weight  #E cotangent weights w_ij
  // rest         #V by 3 rest positions: where anchors stay, and the centroids free components keep
  // pinned       #P distinct vertex indices in [0, #V) (GaussSolver checks them in the caller's numbering)
  // pin_positions  #P by 3 targets of the pinned vertices
  // progress     optional: the factorization reports to it and stops (Cancelled) when it is cancelled
  // Throws std::invalid_argument if the sizes disagree, std::runtime_error if L_ff is not numerically
  // positive definite, OutOfMemory or Cancelled (CholeskySolver::factor).
  ConstrainedLaplacian(const MeshTopology& topo, const std::vector<double>& edge_weight,
                       const std::vector<Eigen::Vector3d>& rest, const std::vector<int64_t>& pinned,
                       const std::vector<Eigen::Vector3d>& pin_positions, Progress* progress = nullptr);

  // New targets for the same pins (#P by 3, in the order of `pinned`): updates the constant
  // right-hand side, never re-factors. Throws std::invalid_argument if the count differs from #P.
  void set_pin_positions(const std::vector<Eigen::Vector3d>& pin_positions);
  // X: #V by 3; writes the pin targets into it (the other rows are left as they are).
  void place_pins(std::vector<Eigen::Vector3d>& X) const;

  int num_unknowns() const { return static_cast<int>(vertex_of_unknown_.size()); }
  int vertex_of_unknown(int u) const { return vertex_of_unknown_[u]; }
  // -L_fp x_p of unknown u: the fixed neighbours' part of its right-hand side.
  const Eigen::Vector3d& constant_rhs(int u) const { return constant_rhs_[u]; }
  // The whole right-hand side of unknown u for the next solve(). Distinct u may be set concurrently.
  void set_rhs(int u, const Eigen::Vector3d& b) {
    double* r = &rhs_[3 * static_cast<size_t>(cholesky_.position(u))];  // elimination order
    r[0] = b.x();
    r[1] = b.y();
    r[2] = b.z();
  }
  // Solves L_ff x_f = rhs and writes x_f into X (#V by 3); puts every anchor at its rest position and
  // translates every component without a pin so that its centroid is its rest centroid. Pins and
  // unreferenced vertices are not touched. Consumes the right-hand side. No allocation.
  void solve(std::vector<Eigen::Vector3d>& X);

  // For a solve with extra terms on a few unknowns (contact_springs.h), built from the parts of solve():
  // the right-hand side in elimination order (row position(u) holds unknown u's x, y, z), L_ff^-1
  // applied in place to any such buffer, and the end of solve() on a right-hand side already solved.
  double* rhs_data() { return rhs_.data(); }
  int position(int u) const { return cholesky_.position(u); }
  void solve_ordered_in_place(double* Y) const { cholesky_.solve_ordered_in_place(Y); }
  void plan_sparse(const int* rows, int count, std::vector<int>& plan) const { cholesky_.plan_sparse(rows, count, plan); }
  void solve_planned_in_place(double* Y, const std::vector<int>& plan) const { cholesky_.solve_planned_in_place(Y, plan); }
  long long plan_nonzeros(const std::vector<int>& plan) const { return cholesky_.plan_nonzeros(plan); }
  void finish_solve(std::vector<Eigen::Vector3d>& X);
  // The unknown of vertex v, -1 for a fixed or unreferenced vertex; L_ff's diagonal at unknown u (the
  // sum of the weights of the unknown's edges).
  int unknown_of_vertex(int v) const { return unknown_of_vertex_[v]; }
  double diagonal(int u) const { return diagonal_[u]; }
  // The translation the last solve() gave vertex v's component (zero for a component with a pin).
  Eigen::Vector3d last_shift(int v) const {
    return free_component_[v] >= 0 ? component_shift_[free_component_[v]] : Eigen::Vector3d::Zero();
  }

  long long factor_nonzeros() const { return cholesky_.factor_nonzeros(); }

 private:
  // An edge between an unknown and a fixed vertex: w * (the fixed vertex's position) goes into the
  // unknown's constant right-hand side.
  struct Coupling {
    int unknown, fixed;  // fixed: index into fixed_position_
    double weight;
  };
  void update_constant_rhs();

  int num_pins_ = 0;
  std::vector<int> pinned_;                         // #P
  std::vector<Eigen::Vector3d> fixed_position_;     // pins (#P, in pin order), then anchors
  std::vector<Coupling> couplings_;                 // in edge order (so the sums are always the same)
  std::vector<int> vertex_of_unknown_;
  std::vector<int> unknown_of_vertex_;              // #V, -1 for fixed and unreferenced vertices
  std::vector<double> diagonal_;                    // #unknowns: L_ff's diagonal
  std::vector<Eigen::Vector3d> constant_rhs_;       // #unknowns
  std::vector<double> rhs_;                         // #unknowns by 3, elimination order
  CholeskySolver cholesky_;

  // Components without a pin.
  std::vector<int> free_component_;                 // #V: the vertex's component if it has no pin, else -1
  std::vector<int> anchor_vertex_;                  // anchor a sits at fixed_position_[#P + a]
  std::vector<Eigen::Vector3d> component_rest_center_;
  std::vector<int> component_size_;
  std::vector<Eigen::Vector3d> component_shift_;    // per step: rest centroid - current centroid
};

}  // namespace gauss
