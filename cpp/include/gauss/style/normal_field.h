#pragma once
// The discrete-normal part of the preference function g (paper Eqs. 9-10) for styles with many
// preferred normals, at a cost that does not grow with their number:
//
//   g(x) = sum_j w_j exp(sigma (x.m_j - 1))
//
// over nodes m_j chosen by where the K input normals lie, with weights solving Eq. 10 (g = 1 at the
// nodes) up to a small ridge, and terms skipped where their kernel is negligible.
//
// Set-up (the constructor), with the kernel width s = 1/sqrt(sigma):
//  1. A geodesic lattice (sphere_lattice.h) of spacing <= kLatticeSpacing s; each input normal counts
//     towards its nearest lattice node. Where a node and all its lattice neighbours hold at least
//     kCoreCount normals, the normals cover the sphere densely, g is a plateau there, and the lattice
//     node stands for them (a regular plateau is flatter and better conditioned than one collocated on
//     the irregular normals: docs/performance.md#figures-behind-the-codes-choices).
//  2. The other normals are merged (direction_merge.h): at kSparseMerge widths in lattice cells with at
//     most kSparseCount normals (sparse normals keep a node each: Eq. 10 nearly exactly), at
//     kDenseMerge widths in fuller cells (the rim of a dense region, a tight bunch). Merge angles are
//     doubled until the kernel matrix fits kMaxEntries and the check kMaxChecks.
//  3. Weights: (A + kRidge I) w = 1 on the nodes (kernel_system.h: truncated at kSolveTruncation,
//     Schwarz-preconditioned CG).
//  4. Check: g at every input normal. While some miss 1 by more than kRefineTarget (at most
//     kMaxRefinements times), the worst of them per lattice cell become nodes, the weights within
//     kRefineRadius widths of those are solved again with the rest held, and g is updated where it moved.
// Tolerance: |g(n_k) - 1| <= max_input_error() at every input normal, measured; <= kTolerance for every
// family the tests cover (spread, clustered, mesh face normals, degenerate sets; sigma 1e-3 to 1e3).
// Why 1e-2 and not less: exact Eq. 10 on normals closer than a kernel width has huge, alternating
// weights, which the ridge bounds at the price of g = 1 - kRidge w_i at node i, and merging adds its
// share where normals crowd (figures: docs/performance.md#figures-behind-the-codes-choices). The
// truncated terms change g by at most truncation_bound(), its gradient by sigma and its Hessian by
// sigma^2 times that.
//
// Evaluation: a NodeGrid lists, per cell, the nodes within reach (kernel >= kTruncation); x reads its
// own cell's list.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "gauss/style/node_grid.h"

namespace gauss {

class SphereLattice;

class NormalField {
 public:
  static constexpr double kTruncation = 1e-10;     // kernel values below this are skipped
  // The weight solve drops more, for a cheaper solve: g at a node then differs from the solved
  // system's by at most 1e-7 sum |w_j| over the extra nodes, which the check sees (measured:
  // docs/performance.md#figures-behind-the-codes-choices).
  static constexpr double kSolveTruncation = 1e-7;
  static constexpr double kTolerance = 1e-2;       // stated bound on |g(n_k) - 1| (see above)
  static constexpr double kRefineTarget = 5e-3;    // refinement stops below this: half the tolerance
  static constexpr double kRidge = 1e-4;           // see above and kernel_system.h
  // Lattice spacing in kernel widths: the widest whose plateau is still flat, as the step sums every
  // node at small sigma (measured: docs/performance.md#figures-behind-the-codes-choices).
  static constexpr double kLatticeSpacing = 1.2;
  // A lattice node stands for the normals near it when it and its neighbours hold at least this many,
  // so that single normals a cell apart do not make a rippling plateau
  // (docs/performance.md#figures-behind-the-codes-choices).
  static constexpr int kCoreCount = 2;
  static constexpr int kSparseCount = 8;           // normals in a lattice cell for it to count as sparse
  static constexpr double kSparseMerge = 0.03;     // widths: closer, the ridge merges them anyway
  static constexpr double kDenseMerge = 0.25;      // widths: a node per quarter width where normals crowd
  static constexpr double kMaxMergeAngle = 0.785;  // radians (merge_directions takes up to pi/2)
  static constexpr int kMaxRefinements = 3;
  static constexpr double kRefineRadius = 5;       // widths: beyond it a new node's kernel is < 4e-6
  static constexpr size_t kMaxEntries = 8'000'000;   // kernel matrix entries (memory: ~100 MB)
  static constexpr size_t kMaxChecks = 128'000'000;  // candidates scanned by the check (time)

  // How the set-up went (for tests and benchmarks).
  struct Stats {
    int lattice_frequency = 0, lattice_nodes = 0, data_nodes = 0, refinements = 0, iterations = 0;
    double merge_scale = 1;  // factor the merge angles were raised by to fit kMaxEntries
  };

  // normals: #K unit vectors (K >= 1); sigma > 0; scale multiplies every weight (a ring style's axis
  // contribution). Throws std::invalid_argument otherwise.
  NormalField(const std::vector<Eigen::Vector3d>& normals, double sigma, double scale = 1.0);

  // Adds the truncated sums over the nodes near x, with e_j = w_j exp(sigma (x.m_j - 1)):
  // sums[0] += sum e_j; sums[1..3] += sum e_j m_j; sums[4..9] += sum e_j (m_j m_j^T)'s upper
  // triangle (xx, xy, xz, yy, yz, zz). Then g = sums[0], grad = sigma sums[1..3], Hess = sigma^2 ...
  void accumulate(const Eigen::Vector3d& x, double sums[10]) const;
  double value(const Eigen::Vector3d& x) const;  // g alone (scaled)

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  const std::vector<Eigen::Vector3d>& nodes() const { return nodes_; }
  const std::vector<double>& weights() const { return weights_; }  // scaled
  double truncation_bound() const { return truncation_bound_; }
  double max_input_error() const { return max_input_error_; }     // before scaling
  const Stats& stats() const { return stats_; }

 private:
  // Set-up steps (see above); they read and write grid_ and stats_.
  std::vector<Eigen::Vector3d> choose_nodes(const std::vector<Eigen::Vector3d>& normals, const std::vector<int>& cell,
                                            const SphereLattice& lattice, double width);
  void add_worst(const std::vector<Eigen::Vector3d>& normals, const std::vector<int>& cell,
                 const std::vector<double>& error, double width, std::vector<Eigen::Vector3d>& nodes) const;
  // Returns, per grid cell, whether g there may have changed.
  std::vector<char> resolve_around(const std::vector<Eigen::Vector3d>& nodes, size_t first_new,
                                   const SphereLattice& lattice, double solve_cutoff, double width,
                                   std::vector<double>& w);
  void set_nodes(const std::vector<Eigen::Vector3d>& nodes, const std::vector<double>& w);
  // What g at x gains when node j's weight changes by delta[j] (#M).
  double change(const Eigen::Vector3d& x, const std::vector<double>& delta) const;

  double sigma_, cutoff_;  // terms with x.m < cutoff_ are skipped
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<double> weights_;
  NodeGrid grid_;
  // Per node, for the hot loop: m (3), the upper triangle of m m^T (6), w.
  std::vector<std::array<double, 10>> terms_;
  std::vector<std::array<double, 4>> points_;  // m, w: what value() reads
  double truncation_bound_ = 0, max_input_error_ = 0;
  Stats stats_;
};

}  // namespace gauss
