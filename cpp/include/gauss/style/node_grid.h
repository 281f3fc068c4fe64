#pragma once
// Which nodes (unit vectors) lie within reach of a point of the unit sphere: the candidates of a sum
// over a truncated kernel (NormalField's evaluation, its check at the input normals, its kernel matrix).
//
// A 3D grid over [-1, 1]^3 with kCellsPerReach cells per reach (at most kMaxCellsPerAxis per axis);
// every cell that meets the sphere lists, in increasing order, each node within `reach` (chord) of
// some point of the cell. A point reads its own cell's list and filters it by its exact distance, so
// a query costs the nodes near it, not the number of nodes.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace gauss {

class NodeGrid {
 public:
  static constexpr int kCellsPerReach = 3;
  static constexpr int kMaxCellsPerAxis = 64;

  NodeGrid() = default;
  // reach: chord length > 0; at 2 or more every node is within reach of every point (one cell).
  explicit NodeGrid(double reach);

  // Cell of a point of [-1, 1]^3 (points outside are clamped onto the border cells).
  int cell(const Eigen::Vector3d& x) const;

  // Lists the nodes (#M unit vectors) per cell. Returns false, listing nothing, when the lists would
  // hold more than max_entries indices in all (the caller's memory budget).
  bool build(const std::vector<Eigen::Vector3d>& nodes, size_t max_entries);

  // The candidates for a point in cell c: node indices [begin, end), increasing.
  const int* begin(int c) const { return list_.data() + start_[c]; }
  const int* end(int c) const { return list_.data() + start_[c + 1]; }
  size_t entries() const { return list_.size(); }  // indices held by all lists (their memory)
  double reach() const { return reach_; }
  int num_cells() const { return static_cast<int>(start_.size()) - 1; }

  // Per cell: whether its list holds a node j with flag[j] (#M flags, one per node built on).
  std::vector<char> cells_listing(const std::vector<char>& flag) const;

 private:
  double reach_ = 2.0;
  int cells_ = 1;
  double cell_size_ = 2.0;
  std::vector<char> meets_;  // per cell: meets the sphere
  std::vector<size_t> start_ = {0, 0};
  std::vector<int> list_;
  int coordinate(double v) const;
};

}  // namespace gauss
