#pragma once
// The weight equalization of Eq. 10 on a set of nodes, regularized:
//
//   (A + ridge I) w = 1,   A_ij = exp(sigma (m_i . m_j - 1)), entries below exp(sigma (cutoff - 1)) dropped,
//
// solved by conjugate gradients preconditioned with overlapping local solves (additive Schwarz).
//
// Why the ridge: Eq. 10 on normals closer than a kernel width is nearly singular, its weights huge
// and alternating, which makes g wild between the normals and the solve slow. With the ridge, g
// misses 1 at node i by exactly ridge * w_i, and the condition number is at most about
// (row sum) / ridge (measured: docs/performance.md#figures-behind-the-codes-choices).
// Why Schwarz: the small eigenvalues of A belong to modes that alternate from node to node, which a
// dense solve over a few neighbouring nodes captures, so CG needs far fewer iterations than with
// diagonal scaling (docs/performance.md#figures-behind-the-codes-choices).
//
// Deterministic for any thread count: rows and patches are computed independently, and every sum over
// nodes is taken in fixed chunks, added in a fixed order.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gauss/style/node_grid.h"

namespace gauss {

class KernelSystem {
 public:
  // Nodes per patch at most: a dense solve's cost and memory grow with its size cubed and squared.
  static constexpr int kMaxPatch = 64;

  // nodes: #M unit vectors; sigma > 0; cutoff: dot products below it are dropped; ridge > 0;
  // grid: a NodeGrid built on `nodes` whose reach covers the cutoff;
  // patches: lists of node indices (a node may be in several; a node in none is scaled by its
  //   diagonal), in priority order: one longer than kMaxPatch keeps its first kMaxPatch.
  KernelSystem(const std::vector<Eigen::Vector3d>& nodes, double sigma, double cutoff, double ridge,
               const NodeGrid& grid, const std::vector<std::vector<int>>& patches);

  // w: #M start values in, solution out; b: #M right-hand side (empty: all 1). Iterates until
  // max_i |b_i - ((A + ridge I) w)_i| <= tolerance or max_iterations; returns that largest residual
  // (recomputed from w, not CG's running one).
  double solve(std::vector<double>& w, const std::vector<double>& b, double tolerance, int max_iterations);

  // Shepard's weights 1 / (row sum of A + ridge): a plateau on evenly spread nodes, CG's usual start.
  std::vector<double> shepard() const;

  int size() const { return static_cast<int>(row_start_.size()) - 1; }
  size_t entries() const { return cols_.size(); }  // kept matrix entries
  int iterations() const { return iterations_; }   // of the last solve

 private:
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;      // y = (A + ridge I) x
  void precondition(const std::vector<double>& r, std::vector<double>& z);        // z = M^-1 r
  double ridge_;
  std::vector<size_t> row_start_;  // CSR of A (without the ridge)
  std::vector<int> cols_;
  std::vector<double> values_;
  // Patches: their nodes, and each one's inverse (b by b, column-major) in one buffer.
  std::vector<size_t> patch_start_, factor_start_;
  std::vector<int> patch_nodes_;
  std::vector<double> factors_, patch_values_;
  std::vector<char> usable_;   // per patch: its factor exists
  std::vector<char> covered_;  // per node: in some usable patch
  int iterations_ = 0;
};

}  // namespace gauss
