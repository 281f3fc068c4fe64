#pragma once
// A geodesic lattice on the unit sphere: the icosahedron's 20 faces each split into n^2 triangles
// (class I geodesic grid of frequency n) and projected onto the sphere, 10 n^2 + 2 nodes.
//
// Why NormalField uses it: where preferred normals cover the sphere densely, g is a plateau of height
// 1, and Gaussian bumps on nearly evenly spaced nodes reproduce a plateau with far less ripple, and a
// better-conditioned kernel matrix, than bumps on the (irregular) data
// (measured: docs/performance.md#figures-behind-the-codes-choices).
// Its cells (each node's nearest points) also give the cheap local statistics NormalField needs: how
// many normals fall near each node, and which nodes are neighbours.
#include <Eigen/Core>
#include <vector>

namespace gauss {

class SphereLattice {
 public:
  static constexpr int kMaxFrequency = 64;  // 40,962 nodes; sigma <= 1e3 needs 32 (settings.h)

  // The lattice of frequency n in [1, kMaxFrequency]; throws std::invalid_argument otherwise.
  explicit SphereLattice(int frequency);

  // The smallest frequency whose mean spacing sqrt(4 pi / (sqrt(3)/2 #nodes)) is at most `angle`
  // radians (> 0), capped at kMaxFrequency.
  static int frequency_for_spacing(double angle);

  int frequency() const { return frequency_; }
  int size() const { return static_cast<int>(nodes_.size()); }
  const std::vector<Eigen::Vector3d>& nodes() const { return nodes_; }  // #N unit vectors
  double mean_spacing() const;                                          // radians

  // The lattice neighbours of node i (5 at the icosahedron's vertices, else 6): [begin, end).
  const int* neighbors_begin(int i) const { return neighbors_.data() + neighbor_start_[i]; }
  const int* neighbors_end(int i) const { return neighbors_.data() + neighbor_start_[i + 1]; }

  // Index of the node nearest to x (a unit vector); ties go to the smaller index. O(1).
  int nearest(const Eigen::Vector3d& x) const;

 private:
  int frequency_;
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<int> neighbor_start_, neighbors_;  // CSR
  // Lookup grid over [-1, 1]^3 with cells as wide as the longest edge (chord), which exceeds the
  // distance from any point of the sphere to its nearest node: the 27 cells around x hold it.
  int cells_ = 1;
  double cell_size_ = 2.0;
  std::vector<int> cell_start_, cell_nodes_;
  int cell_coordinate(double v) const;
};

}  // namespace gauss
