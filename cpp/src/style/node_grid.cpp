#include "gauss/style/node_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gauss {

using Eigen::Vector3d;

NodeGrid::NodeGrid(double reach) : reach_(reach) {
  if (!(reach > 0)) throw std::invalid_argument("NodeGrid needs a positive reach");
  cells_ = reach >= 2.0 ? 1 : std::clamp(static_cast<int>(std::ceil(2.0 * kCellsPerReach / reach)), 1, kMaxCellsPerAxis);
  cell_size_ = 2.0 / cells_;
  const size_t num_cells = static_cast<size_t>(cells_) * cells_ * cells_;
  start_.assign(num_cells + 1, 0);
  // The cells that meet the sphere: their centre lies within half a diagonal of it.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * cell_size_;
  const double lo2 = std::pow(std::max(0.0, 1.0 - half_diagonal), 2), hi2 = std::pow(1.0 + half_diagonal, 2);
  auto centre = [&](int i) { return (i + 0.5) * cell_size_ - 1.0; };
  meets_.assign(num_cells, 0);
  for (int z = 0; z < cells_; ++z)
    for (int y = 0; y < cells_; ++y)
      for (int x = 0; x < cells_; ++x) {
        const double c2 = centre(x) * centre(x) + centre(y) * centre(y) + centre(z) * centre(z);
        meets_[x + static_cast<size_t>(cells_) * (y + static_cast<size_t>(cells_) * z)] = c2 >= lo2 && c2 <= hi2;
      }
}

int NodeGrid::coordinate(double v) const {
  return std::clamp(static_cast<int>(std::floor((v + 1.0) / cell_size_)), 0, cells_ - 1);
}

int NodeGrid::cell(const Vector3d& x) const {
  return coordinate(x.x()) + cells_ * (coordinate(x.y()) + cells_ * coordinate(x.z()));
}

bool NodeGrid::build(const std::vector<Vector3d>& nodes, size_t max_entries) {
  const size_t num_cells = static_cast<size_t>(cells_) * cells_ * cells_;
  std::vector<size_t> start(num_cells + 1, 0);
  std::vector<int> list;
  if (cells_ == 1) {  // everything within reach of everything
    if (nodes.size() > max_entries) return false;
    list.resize(nodes.size());
    for (size_t j = 0; j < nodes.size(); ++j) list[j] = static_cast<int>(j);
    start[1] = list.size();
  } else {
    // A node belongs to the list of every cell that meets the sphere (its centre lies within half a
    // diagonal of it) and whose centre lies within reach + half a diagonal of the node (so some point
    // of the cell is within reach). Per row of cells the second condition is an interval of x, so
    // only cells inside the ball are visited. Counted, then filled: the lists come out in node order.
    const double half_diagonal = 0.5 * std::sqrt(3.0) * cell_size_, radius = reach_ + half_diagonal;
    const double r2 = radius * radius;
    auto centre = [&](int i) { return (i + 0.5) * cell_size_ - 1.0; };
    auto for_cells_of = [&](const Vector3d& m, auto&& f) {
      for (int z = coordinate(m.z() - radius), z1 = coordinate(m.z() + radius); z <= z1; ++z) {
        const double dz = centre(z) - m.z();
        for (int y = coordinate(m.y() - radius), y1 = coordinate(m.y() + radius); y <= y1; ++y) {
          const double dy = centre(y) - m.y(), left = r2 - dz * dz - dy * dy;
          if (left < 0) continue;
          const double dx = std::sqrt(left);
          // centres within [m.x - dx, m.x + dx]: (i + 0.5) cell - 1 in that range
          const int x0 = std::max(0, static_cast<int>(std::ceil((m.x() - dx + 1.0) / cell_size_ - 0.5)));
          const int x1 = std::min(cells_ - 1, static_cast<int>(std::floor((m.x() + dx + 1.0) / cell_size_ - 0.5)));
          const size_t row = static_cast<size_t>(cells_) * (y + static_cast<size_t>(cells_) * z);
          for (int x = x0; x <= x1; ++x)
            if (meets_[row + x]) f(row + x);
        }
      }
    };
    for (const Vector3d& m : nodes) for_cells_of(m, [&](size_t c) { ++start[c + 1]; });
    for (size_t c = 0; c < num_cells; ++c) start[c + 1] += start[c];
    if (start[num_cells] > max_entries) return false;
    list.resize(start[num_cells]);
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    for (size_t j = 0; j < nodes.size(); ++j)
      for_cells_of(nodes[j], [&](size_t c) { list[fill[c]++] = static_cast<int>(j); });
  }
  start_ = std::move(start);
  list_ = std::move(list);
  return true;
}

std::vector<char> NodeGrid::cells_listing(const std::vector<char>& flag) const {
  std::vector<char> out(num_cells(), 0);
  for (int c = 0; c < num_cells(); ++c)
    for (const int* j = begin(c); j != end(c) && !out[c]; ++j) out[c] = flag[*j];
  return out;
}

}  // namespace gauss
