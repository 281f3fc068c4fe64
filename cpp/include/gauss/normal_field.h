#pragma once
// The discrete-normal part of the preference function g (paper Eqs. 9-10) for styles with many
// preferred normals, at a cost that does not grow with their number:
//
//   g(x) = sum_j w_j exp(sigma (x.m_j - 1))
//
// over nodes m_j that stand for clusters of near-parallel input normals, with the weights solved so
// that g = 1 at every input normal (Eq. 10) and terms skipped where their kernel is negligible.
//
// Set-up (the constructor):
//  1. Merge (direction_merge.h) at kCoarseMerge kernel widths (width 1/sqrt(sigma), at most
//     kMaxMergeAngle): inside a densely covered region g is a plateau that coarse nodes reproduce.
//  2. Solve the weights on the nodes, A w = 1 with A_ij = exp(sigma (m_i.m_j - 1)) truncated below
//     kTruncation: sparse, preconditioned conjugate gradients, no dense #K by #K matrix.
//  3. Evaluate g at every input normal; the clusters with a normal off by more than kTolerance are
//     merged again at half the angle, down to kFineMerge widths, and 2-3 repeat.
// Tolerances (measured at set-up and readable): |g(n_k) - 1| <= kTolerance at every input normal
// unless the clusters could not be refined further (max_input_error() says what was reached); the
// skipped terms change g by at most truncation_bound(), its gradient by sigma and its Hessian by
// sigma^2 times that.
//
// Evaluation: a 3D grid over [-1, 1]^3, kCellsPerReach cells per reach of the truncated kernel; each
// cell that meets the sphere lists the nodes within reach of it, so x only reads its own cell's list.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace gauss {

class NormalField {
 public:
  static constexpr double kTruncation = 1e-10;   // kernel values below this are skipped
  static constexpr double kTolerance = 1e-3;     // target for |g(n_k) - 1| at the input normals
  static constexpr double kCoarseMerge = 1.0;    // first merge angle, in kernel widths
  static constexpr double kFineMerge = 1.0 / 4;  // finest merge angle, in kernel widths
  static constexpr double kMaxMergeAngle = 0.25; // radians: wide kernels (small sigma) merge no wider

  // normals: #K unit vectors (K >= 1); sigma > 0; scale multiplies every weight (a ring style's axis
  // contribution).
  NormalField(const std::vector<Eigen::Vector3d>& normals, double sigma, double scale = 1.0);

  // Adds the truncated sums over the nodes near x, with e_j = w_j exp(sigma (x.m_j - 1)):
  // sums[0] += sum e_j; sums[1..3] += sum e_j m_j; sums[4..9] += sum e_j (m_j m_j^T)'s upper
  // triangle (xx, xy, xz, yy, yz, zz). Then g = sums[0], grad = sigma sums[1..3], Hess = sigma^2 ...
  void accumulate(const Eigen::Vector3d& x, double sums[10]) const;

  int num_nodes() const { return static_cast<int>(terms_.size()); }
  const std::vector<Eigen::Vector3d>& nodes() const { return nodes_; }
  const std::vector<double>& weights() const { return weights_; }
  double truncation_bound() const { return truncation_bound_; }
  double max_input_error() const { return max_input_error_; }

 private:
  // Sorts nodes_ by grid cell and fills the grid; returns the old index of each sorted node.
  std::vector<int> build_grid();
  // start: initial weights per node (NaN: Shepard's 1 / row sum). Returns the largest |A w - 1|.
  double solve_weights(const std::vector<double>& start);
  double value(const Eigen::Vector3d& x) const;

  double sigma_, cutoff_;  // terms with x.m < cutoff_ are skipped
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<double> weights_;
  // Grid: node order by cell (x fastest), terms as in PreferenceFunction: m (3), m m^T upper (6), w.
  static constexpr int kCellsPerReach = 3;
  static constexpr int kMaxCellsPerAxis = 64;
  int cell_index(const Eigen::Vector3d& x) const;
  int cells_ = 1;
  double cell_size_ = 2.0;
  std::vector<int> list_start_, list_;  // per cell: the nodes within reach (CSR)
  std::vector<std::array<double, 10>> terms_;
  double truncation_bound_ = 0, max_input_error_ = 0;
};

}  // namespace gauss
