#include "gauss/style/normal_field.h"
#include "gauss/util/constants.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "gauss/style/direction_merge.h"
#include "gauss/style/kernel_system.h"
#include "gauss/util/parallel.h"
#include "gauss/style/sphere_lattice.h"

namespace gauss {
namespace {

using Eigen::Vector3d;

constexpr int kNodesParallelMin = 1024;
// CG stops when every node's residual 1 - ((A + ridge I) w)_i is below this: a fifth of the
// refinement target, as a tighter one costs iterations without moving the errors at the normals
// (measured: docs/performance.md#figures-behind-the-codes-choices).
constexpr double kSolveTolerance = 1e-3;
constexpr int kMaxIterations = 300;

// Appends the directions of normals[subset] merged at `angle` radians (capped) to `out`.
void append_merged(const std::vector<Vector3d>& normals, const std::vector<int>& subset, double angle,
                   std::vector<Vector3d>& out) {
  if (subset.empty()) return;
  const MergedDirections md = merge_directions(normals, {}, subset, std::min(angle, NormalField::kMaxMergeAngle));
  out.insert(out.end(), md.directions.begin(), md.directions.end());
}

// Sorts nodes by grid cell: neighbouring lookups then read neighbouring memory.
void sort_by_cell(const NodeGrid& grid, std::vector<Vector3d>& nodes) {
  std::vector<std::pair<int, int>> key(nodes.size());
  for (size_t j = 0; j < nodes.size(); ++j) key[j] = {grid.cell(nodes[j]), static_cast<int>(j)};
  std::sort(key.begin(), key.end());
  std::vector<Vector3d> sorted(nodes.size());
  for (size_t j = 0; j < nodes.size(); ++j) sorted[j] = nodes[key[j].second];
  nodes.swap(sorted);
}

// Schwarz patches: per lattice node, the nodes nearest to it or to its lattice neighbours, nearest
// to it first.
std::vector<std::vector<int>> lattice_patches(const SphereLattice& lattice, const std::vector<Vector3d>& nodes) {
  const int M = static_cast<int>(nodes.size());
  std::vector<int> home(M);
  parallel::for_each(M, kNodesParallelMin, [&](int j) { home[j] = lattice.nearest(nodes[j]); });
  std::vector<std::vector<int>> members(lattice.size());
  for (int j = 0; j < M; ++j) members[home[j]].push_back(j);
  std::vector<std::vector<int>> patches;
  for (int c = 0; c < lattice.size(); ++c) {
    if (members[c].empty()) continue;
    std::vector<int> p = members[c];
    for (const int* b = lattice.neighbors_begin(c); b != lattice.neighbors_end(c); ++b)
      p.insert(p.end(), members[*b].begin(), members[*b].end());
    const Vector3d& centre = lattice.nodes()[c];
    std::stable_sort(p.begin(), p.end(), [&](int a, int b) { return nodes[a].dot(centre) > nodes[b].dot(centre); });
    patches.push_back(std::move(p));
  }
  return patches;
}

}  // namespace

NormalField::NormalField(const std::vector<Vector3d>& normals, double sigma, double scale) : sigma_(sigma) {
  if (normals.empty() || !(sigma > 0) || !std::isfinite(sigma) || !std::isfinite(scale))
    throw std::invalid_argument("NormalField needs normals, a finite sigma > 0 and a finite scale");
  for (const Vector3d& n : normals)
    if (!n.allFinite() || std::abs(n.squaredNorm() - 1.0) > 1e-6)
      throw std::invalid_argument("NormalField needs unit normals");
  const int K = static_cast<int>(normals.size());
  const double width = 1.0 / std::sqrt(sigma);
  // exp(sigma (t - 1)) < kTruncation  <=>  t < 1 - log(1 / kTruncation) / sigma.
  cutoff_ = 1.0 - std::log(1.0 / kTruncation) / sigma;
  const double solve_cutoff = 1.0 - std::log(1.0 / kSolveTruncation) / sigma;
  const double reach = cutoff_ > -1.0 ? std::sqrt(2.0 * (1.0 - cutoff_)) : 2.0;
  grid_ = NodeGrid(reach);

  // 1-2. The lattice, where the normals fall on it, and the nodes.
  const SphereLattice lattice(SphereLattice::frequency_for_spacing(kLatticeSpacing * width));
  std::vector<int> cell(K);
  parallel::for_each(K, kNodesParallelMin, [&](int k) { cell[k] = lattice.nearest(normals[k]); });
  std::vector<Vector3d> nodes = choose_nodes(normals, cell, lattice, width);
  std::vector<double> w(nodes.size(), 0.0);

  // 3. Weights on all nodes.
  {
    KernelSystem system(nodes, sigma, solve_cutoff, kRidge, grid_, lattice_patches(lattice, nodes));
    w = system.shepard();
    system.solve(w, {}, kSolveTolerance, kMaxIterations);
    stats_.iterations += system.iterations();
  }
  set_nodes(nodes, w);

  // 4. Check at every normal, cell by cell (each cell's list and nodes stay in cache); refine.
  // After a refinement only the weights around the new nodes changed: g is updated by those terms
  // alone, in the grid cells whose lists hold one of them.
  std::vector<double> g_at(K), error(K), delta;  // delta: per node, its weight's change (refinements)
  std::vector<int> input_cell(K), by_cell(K);
  for (int k = 0; k < K; ++k) input_cell[k] = grid_.cell(normals[k]);
  std::iota(by_cell.begin(), by_cell.end(), 0);
  std::stable_sort(by_cell.begin(), by_cell.end(), [&](int a, int b) { return input_cell[a] < input_cell[b]; });
  std::vector<char> changed;  // per grid cell: its g moved
  for (int round = 0;; ++round) {
    parallel::for_each(K, kNodesParallelMin, [&](int i) {
      const int k = by_cell[i];
      if (round == 0)
        g_at[k] = value(normals[k]);
      else if (changed[input_cell[k]])
        g_at[k] += change(normals[k], delta);
      error[k] = std::abs(g_at[k] - 1.0);
    });
    max_input_error_ = *std::max_element(error.begin(), error.end());
    if (!(max_input_error_ > kRefineTarget) || round == kMaxRefinements) break;
    const size_t before = nodes.size();
    add_worst(normals, cell, error, width, nodes);
    if (nodes.size() == before || !grid_.build(nodes, 2 * kMaxEntries)) {
      nodes.resize(before);  // nothing to add, or no room: keep the last round's nodes, lists and error
      break;
    }
    w.resize(nodes.size(), 0.0);
    delta = w;
    changed = resolve_around(nodes, before, lattice, solve_cutoff, width, w);
    for (size_t j = 0; j < w.size(); ++j) delta[j] = w[j] - delta[j];
    set_nodes(nodes, w);
    ++stats_.refinements;
  }
  stats_.lattice_frequency = lattice.frequency();
  stats_.data_nodes = num_nodes() - stats_.lattice_nodes;

  double sum_abs = 0;
  for (size_t j = 0; j < weights_.size(); ++j) {
    weights_[j] *= scale;
    terms_[j][9] = points_[j][3] = weights_[j];
    sum_abs += std::abs(weights_[j]);
  }
  truncation_bound_ = cutoff_ > -1.0 ? kTruncation * sum_abs : 0.0;
}

std::vector<Vector3d> NormalField::choose_nodes(const std::vector<Vector3d>& normals, const std::vector<int>& cell,
                                                const SphereLattice& lattice, double width) {
  // Lattice nodes where they and all their neighbours hold kCoreCount normals or more.
  std::vector<int> count(lattice.size(), 0);
  for (int c : cell) ++count[c];
  std::vector<char> core(lattice.size(), 0);
  std::vector<Vector3d> lattice_nodes;
  for (int c = 0; c < lattice.size(); ++c) {
    bool dense = count[c] >= kCoreCount;
    for (const int* b = lattice.neighbors_begin(c); dense && b != lattice.neighbors_end(c); ++b)
      dense = count[*b] >= kCoreCount;
    core[c] = dense;
    if (dense) lattice_nodes.push_back(lattice.nodes()[c]);
  }
  stats_.lattice_nodes = static_cast<int>(lattice_nodes.size());
  std::vector<int> sparse, crowded;  // the normals the lattice does not stand for
  for (size_t k = 0; k < normals.size(); ++k)
    if (!core[cell[k]]) (count[cell[k]] <= kSparseCount ? sparse : crowded).push_back(static_cast<int>(k));
  // Data nodes, merged more coarsely until the kernel matrix and the check fit the budget: each node
  // reads its cell's list for its matrix row, each normal for its check.
  std::vector<Vector3d> nodes;
  for (double f = 1;; f *= 2) {
    nodes = lattice_nodes;
    append_merged(normals, sparse, kSparseMerge * width * f, nodes);
    append_merged(normals, crowded, kDenseMerge * width * f, nodes);
    sort_by_cell(grid_, nodes);
    const bool coarsest = kSparseMerge * width * f >= kMaxMergeAngle;  // then few data nodes are left
    stats_.merge_scale = f;
    if (!grid_.build(nodes, coarsest ? 4 * kMaxEntries : kMaxEntries)) {
      if (coarsest) throw std::invalid_argument("NormalField: too many nodes");
      continue;
    }
    size_t rows = 0, checks = 0;
    for (const Vector3d& m : nodes) rows += grid_.end(grid_.cell(m)) - grid_.begin(grid_.cell(m));
    for (const Vector3d& n : normals) checks += grid_.end(grid_.cell(n)) - grid_.begin(grid_.cell(n));
    if ((rows <= kMaxEntries && checks <= kMaxChecks) || coarsest) return nodes;
  }
}

void NormalField::add_worst(const std::vector<Vector3d>& normals, const std::vector<int>& cell,
                            const std::vector<double>& error, double width, std::vector<Vector3d>& nodes) const {
  // Per lattice cell, its normals that miss g = 1 by more than kRefineTarget, worst first, become
  // nodes, unless a node lies within kSparseMerge widths (the ridge would merge them anyway) or a
  // node added here within kDenseMerge widths.
  std::vector<int> bad;
  for (size_t k = 0; k < normals.size(); ++k)
    if (error[k] > kRefineTarget) bad.push_back(static_cast<int>(k));
  std::sort(bad.begin(), bad.end(), [&](int a, int b) {
    return cell[a] != cell[b] ? cell[a] < cell[b] : error[a] != error[b] ? error[a] > error[b] : a < b;
  });
  const double near_node = std::cos(kSparseMerge * width), near_new = std::cos(kDenseMerge * width);
  const size_t before = nodes.size();
  for (size_t i = 0, first_of_cell = before; i < bad.size(); ++i) {
    const Vector3d& x = normals[bad[i]];
    if (i > 0 && cell[bad[i]] != cell[bad[i - 1]]) first_of_cell = nodes.size();
    bool free = true;
    const int c = grid_.cell(x);
    for (const int* j = grid_.begin(c); free && j != grid_.end(c); ++j) free = x.dot(nodes[*j]) < near_node;
    for (size_t j = first_of_cell; free && j < nodes.size(); ++j) free = x.dot(nodes[j]) < near_new;
    if (free) nodes.push_back(x);
  }
}

std::vector<char> NormalField::resolve_around(const std::vector<Vector3d>& nodes, size_t first_new,
                                              const SphereLattice& lattice, double solve_cutoff, double width,
                                              std::vector<double>& w) {
  // The nodes within kRefineRadius widths of a new node get their weights solved again, the others
  // held (beyond that radius a new node's kernel is below e^-12.5): Eq. 10 restricted to the region,
  //   (A_RR + ridge I) w_R = 1 - A_R,rest w_rest.
  const int M = static_cast<int>(nodes.size());
  std::vector<char> in_region(M, 0);
  const double region_dot = std::cos(std::min(kRefineRadius * width, kPi));
  for (int q = static_cast<int>(first_new); q < M; ++q) {
    const int c = grid_.cell(nodes[q]);
    for (const int* j = grid_.begin(c); j != grid_.end(c); ++j)
      if (nodes[q].dot(nodes[*j]) >= region_dot) in_region[*j] = 1;
    in_region[q] = 1;
  }
  std::vector<int> region;
  for (int j = 0; j < M; ++j)
    if (in_region[j]) region.push_back(j);
  const int R = static_cast<int>(region.size());
  std::vector<Vector3d> sub(R);
  std::vector<double> sub_w(R), rhs(R);
  for (int i = 0; i < R; ++i) sub[i] = nodes[region[i]], sub_w[i] = w[region[i]];
  parallel::for_each(R, kNodesParallelMin, [&](int i) {
    const Vector3d& m = sub[i];
    const int c = grid_.cell(m);
    double held = 0;
    for (const int* j = grid_.begin(c); j != grid_.end(c); ++j) {
      const double t = m.dot(nodes[*j]);
      if (!in_region[*j] && t >= solve_cutoff) held += w[*j] * std::exp(sigma_ * (t - 1.0));
    }
    rhs[i] = 1.0 - held;
  });
  NodeGrid sub_grid(grid_.reach());
  sub_grid.build(sub, SIZE_MAX);
  KernelSystem system(sub, sigma_, solve_cutoff, kRidge, sub_grid, lattice_patches(lattice, sub));
  system.solve(sub_w, rhs, kSolveTolerance, kMaxIterations);
  stats_.iterations += system.iterations();
  for (int i = 0; i < R; ++i) w[region[i]] = sub_w[i];
  // g moved in the grid cells whose list holds a node of the region.
  return grid_.cells_listing(in_region);
}

void NormalField::set_nodes(const std::vector<Vector3d>& nodes, const std::vector<double>& w) {
  nodes_ = nodes;
  weights_ = w;
  terms_.resize(nodes.size());
  points_.resize(nodes.size());
  for (size_t j = 0; j < nodes.size(); ++j) {
    const Vector3d& n = nodes[j];
    terms_[j] = {n.x(), n.y(), n.z(), n.x() * n.x(), n.x() * n.y(), n.x() * n.z(), n.y() * n.y(),
                 n.y() * n.z(), n.z() * n.z(), w[j]};
    points_[j] = {n.x(), n.y(), n.z(), w[j]};
  }
}

// Both loops below go through a cell's list in chunks: dot products and a branch-free compaction of
// the candidates within reach first, then the exponentials back to back, then the sums. No library
// call in the first loop, so that the compiler keeps x and the sums in registers.
namespace {
constexpr int kReachChunk = 64;
}

void NormalField::accumulate(const Vector3d& x, double sums[10]) const {
  const int cell = grid_.cell(x);
  int index[kReachChunk];
  double e[kReachChunk];
  double v = 0, g0 = 0, g1 = 0, g2 = 0, h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;
  for (const int *j = grid_.begin(cell), *end = grid_.end(cell); j != end;) {
    int m = 0;
    for (const int* stop = j + std::min<std::ptrdiff_t>(kReachChunk, end - j); j != stop; ++j) {
      const std::array<double, 4>& p = points_[*j];
      const double d = x.x() * p[0] + x.y() * p[1] + x.z() * p[2];
      index[m] = *j;
      e[m] = sigma_ * (d - 1.0);
      m += d >= cutoff_;
    }
    for (int i = 0; i < m; ++i) e[i] = std::exp(e[i]);
    for (int i = 0; i < m; ++i) {
      const std::array<double, 10>& t = terms_[index[i]];
      const double c = t[9] * e[i];
      v += c;
      g0 += c * t[0];
      g1 += c * t[1];
      g2 += c * t[2];
      h00 += c * t[3];
      h01 += c * t[4];
      h02 += c * t[5];
      h11 += c * t[6];
      h12 += c * t[7];
      h22 += c * t[8];
    }
  }
  sums[0] += v;
  sums[1] += g0;
  sums[2] += g1;
  sums[3] += g2;
  sums[4] += h00;
  sums[5] += h01;
  sums[6] += h02;
  sums[7] += h11;
  sums[8] += h12;
  sums[9] += h22;
}

double NormalField::change(const Vector3d& x, const std::vector<double>& delta) const {
  // sum over the nodes near x whose weight changed by delta_j of delta_j exp(sigma (x.m_j - 1))
  const int cell = grid_.cell(x);
  double g = 0;
  for (const int *j = grid_.begin(cell), *end = grid_.end(cell); j != end; ++j) {
    if (delta[*j] == 0.0) continue;
    const std::array<double, 4>& p = points_[*j];
    const double d = x.x() * p[0] + x.y() * p[1] + x.z() * p[2];
    if (d >= cutoff_) g += delta[*j] * std::exp(sigma_ * (d - 1.0));
  }
  return g;
}

double NormalField::value(const Vector3d& x) const {
  // g alone (the set-up's check at every input normal): one exponential per node within reach.
  const int cell = grid_.cell(x);
  double w[kReachChunk], e[kReachChunk];
  double g = 0;
  for (const int *j = grid_.begin(cell), *end = grid_.end(cell); j != end;) {
    int m = 0;
    for (const int* stop = j + std::min<std::ptrdiff_t>(kReachChunk, end - j); j != stop; ++j) {
      const std::array<double, 4>& p = points_[*j];
      const double d = x.x() * p[0] + x.y() * p[1] + x.z() * p[2];
      w[m] = p[3];
      e[m] = sigma_ * (d - 1.0);
      m += d >= cutoff_;
    }
    for (int i = 0; i < m; ++i) e[i] = std::exp(e[i]);
    for (int i = 0; i < m; ++i) g += w[i] * e[i];
  }
  return g;
}

}  // namespace gauss
