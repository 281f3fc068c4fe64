#include "gauss/style/sphere_lattice.h"
#include "gauss/util/constants.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace gauss {
namespace {

using Eigen::Vector3d;

const std::array<Vector3d, 12>& icosahedron_vertices() {
  static const std::array<Vector3d, 12> v = [] {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::array<Vector3d, 12> out = {Vector3d(-1, t, 0), Vector3d(1, t, 0),  Vector3d(-1, -t, 0), Vector3d(1, -t, 0),
                                    Vector3d(0, -1, t), Vector3d(0, 1, t),  Vector3d(0, -1, -t), Vector3d(0, 1, -t),
                                    Vector3d(t, 0, -1), Vector3d(t, 0, 1),  Vector3d(-t, 0, -1), Vector3d(-t, 0, 1)};
    for (Vector3d& x : out) x.normalize();
    return out;
  }();
  return v;
}

constexpr int kFaces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9},  {5, 11, 4},
                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6},  {3, 6, 8},
                               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};

}  // namespace

int SphereLattice::frequency_for_spacing(double angle) {
  if (!(angle > 0)) throw std::invalid_argument("lattice spacing must be positive");
  for (int n = 1; n < kMaxFrequency; ++n) {
    const double nodes = 10.0 * n * n + 2.0;
    if (std::sqrt(4.0 * kPi / (0.5 * std::sqrt(3.0) * nodes)) <= angle) return n;
  }
  return kMaxFrequency;
}

double SphereLattice::mean_spacing() const { return std::sqrt(4.0 * kPi / (0.5 * std::sqrt(3.0) * size())); }

SphereLattice::SphereLattice(int n) : frequency_(n) {
  if (n < 1 || n > kMaxFrequency) throw std::invalid_argument("lattice frequency must lie between 1 and 64");
  const auto& V = icosahedron_vertices();
  // Shared points are built once, from canonical data, so that neighbouring faces agree bit for bit:
  // the 12 vertices, then each edge's n - 1 inner points (from its smaller vertex to its larger),
  // then each face's inner points.
  nodes_.assign(V.begin(), V.end());
  std::vector<std::array<int, 3>> edge_of;  // (small vertex, large vertex, first node index)
  auto edge_node = [&](int a, int b, int t) {  // point t of n along a -> b, 0 < t < n
    const bool flip = a > b;
    const int lo = flip ? b : a, hi = flip ? a : b, along = flip ? n - t : t;
    for (const auto& e : edge_of)
      if (e[0] == lo && e[1] == hi) return e[2] + along - 1;
    const int first = size();
    for (int s = 1; s < n; ++s) nodes_.push_back((V[lo] * (n - s) + V[hi] * s).normalized());
    edge_of.push_back({lo, hi, first});
    return first + along - 1;
  };
  // Node index of face f's point with weights (n - i - j, i, j) on its vertices (a, b, c).
  std::vector<int> face_points;
  std::vector<std::pair<int, int>> edges;
  for (const auto& f : kFaces) {
    const int a = f[0], b = f[1], c = f[2];
    auto index = [&](int i, int j) {
      const int k = n - i - j;
      if (i == 0 && j == 0) return a;
      if (k == 0 && j == 0) return b;
      if (k == 0 && i == 0) return c;
      if (j == 0) return edge_node(a, b, i);
      if (i == 0) return edge_node(a, c, j);
      if (k == 0) return edge_node(b, c, j);
      return -1;  // inner: numbered below
    };
    face_points.assign(static_cast<size_t>(n + 1) * (n + 1), -1);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        int id = index(i, j);
        if (id < 0) {
          id = size();
          nodes_.push_back((V[a] * (n - i - j) + V[b] * i + V[c] * j).normalized());
        }
        face_points[i * (n + 1) + j] = id;
      }
    auto at = [&](int i, int j) { return face_points[i * (n + 1) + j]; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const int p = at(i, j), q = at(i + 1, j), r = at(i, j + 1);
        for (auto e : {std::make_pair(p, q), std::make_pair(q, r), std::make_pair(r, p)})
          edges.emplace_back(std::min(e.first, e.second), std::max(e.first, e.second));
      }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const int N = size();
  neighbor_start_.assign(N + 1, 0);
  for (const auto& [p, q] : edges) ++neighbor_start_[p + 1], ++neighbor_start_[q + 1];
  for (int i = 0; i < N; ++i) neighbor_start_[i + 1] += neighbor_start_[i];
  neighbors_.resize(neighbor_start_[N]);
  std::vector<int> fill(neighbor_start_.begin(), neighbor_start_.end() - 1);
  double longest = 0;
  for (const auto& [p, q] : edges) {
    neighbors_[fill[p]++] = q;
    neighbors_[fill[q]++] = p;
    longest = std::max(longest, (nodes_[p] - nodes_[q]).norm());
  }
  for (int i = 0; i < N; ++i) std::sort(neighbors_.begin() + neighbor_start_[i], neighbors_.begin() + neighbor_start_[i + 1]);

  cells_ = std::max(1, static_cast<int>(std::floor(2.0 / longest)));
  cell_size_ = 2.0 / cells_;
  cell_start_.assign(static_cast<size_t>(cells_) * cells_ * cells_ + 1, 0);
  auto cell_of = [&](const Vector3d& x) {
    return cell_coordinate(x.x()) + cells_ * (cell_coordinate(x.y()) + cells_ * cell_coordinate(x.z()));
  };
  for (const Vector3d& x : nodes_) ++cell_start_[cell_of(x) + 1];
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_nodes_.resize(N);
  fill.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < N; ++i) cell_nodes_[fill[cell_of(nodes_[i])]++] = i;
}

int SphereLattice::cell_coordinate(double v) const {
  return std::clamp(static_cast<int>(std::floor((v + 1.0) / cell_size_)), 0, cells_ - 1);
}

int SphereLattice::nearest(const Vector3d& x) const {
  const int cx = cell_coordinate(x.x()), cy = cell_coordinate(x.y()), cz = cell_coordinate(x.z());
  int best = -1;
  double best_dot = -2.0;
  for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, cells_ - 1); ++z)
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, cells_ - 1); ++y)
      for (int c = cells_ * (y + cells_ * z) + std::max(cx - 1, 0), end = cells_ * (y + cells_ * z) + std::min(cx + 1, cells_ - 1);
           c <= end; ++c)
        for (int l = cell_start_[c]; l < cell_start_[c + 1]; ++l) {
          const int i = cell_nodes_[l];
          const double d = x.dot(nodes_[i]);
          if (d > best_dot || (d == best_dot && i < best)) best_dot = d, best = i;
        }
  if (best < 0)  // only for x off the sphere (NaN, or far from unit length): scan everything
    for (int i = 0; i < size(); ++i)
      if (best < 0 || x.dot(nodes_[i]) > best_dot) best_dot = x.dot(nodes_[i]), best = i;
  return best;
}

}  // namespace gauss
