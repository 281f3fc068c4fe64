#include "gauss/normal_field.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "gauss/direction_merge.h"
#include "gauss/parallel.h"

namespace gauss {
namespace {

using Eigen::Vector3d;

// Conjugate gradients stop when g is this close to 1 at every node, or after kMaxIterations (the
// kernel matrix of close nodes is ill-conditioned; stopping early is what keeps the weights tame).
constexpr double kSolveTolerance = 1e-7;
constexpr int kMaxIterations = 400;
// Ridge added to the kernel matrix's diagonal (its entries are <= 1): nodes closer than a kernel
// width make A ill-conditioned and its exact weights huge and alternating; the ridge bounds the
// condition number by about (row sum) / kRidge and moves g at a node by kRidge w, well inside
// kTolerance.
constexpr double kRidge = 1e-4;
// Memory cap of the truncated kernel matrix: a cluster is not refined when that would exceed it.
constexpr long long kMaxKernelEntries = 8'000'000;
constexpr int kParallelMin = 1024;

struct Cluster {
  Vector3d node;
  std::vector<int> members;  // indices of input normals
  double angle;              // merge angle that made it
  double weight = NAN;       // solved weight (NaN: new, not solved yet)
};

std::vector<Cluster> clusters_of(const std::vector<Vector3d>& normals, const std::vector<int>& subset, double angle) {
  const MergedDirections md = merge_directions(normals, {}, subset, angle);
  std::vector<Cluster> out(md.directions.size());
  for (size_t c = 0; c < out.size(); ++c) out[c] = {md.directions[c], {}, angle, NAN};
  for (size_t i = 0; i < subset.size(); ++i) out[md.cluster_of[i]].members.push_back(subset[i]);
  return out;
}

}  // namespace

NormalField::NormalField(const std::vector<Vector3d>& normals, double sigma, double scale) : sigma_(sigma) {
  if (normals.empty() || !(sigma > 0)) throw std::invalid_argument("NormalField needs normals and sigma > 0");
  // exp(sigma (t - 1)) < kTruncation  <=>  t < 1 - log(1 / kTruncation) / sigma.
  cutoff_ = 1.0 - std::log(1.0 / kTruncation) / sigma;
  const double width = 1.0 / std::sqrt(sigma);
  const double first_angle = std::min(kCoarseMerge * width, kMaxMergeAngle);
  const double finest_angle = first_angle * (kFineMerge / kCoarseMerge);
  std::vector<int> all(normals.size());
  std::iota(all.begin(), all.end(), 0);
  std::vector<Cluster> clusters = clusters_of(normals, all, first_angle);
  std::vector<double> error(normals.size());
  for (;;) {
    nodes_.resize(clusters.size());
    for (size_t c = 0; c < clusters.size(); ++c) nodes_[c] = clusters[c].node;
    const std::vector<int> cluster_at = build_grid();
    std::vector<double> start(clusters.size());
    for (size_t j = 0; j < clusters.size(); ++j) start[j] = clusters[cluster_at[j]].weight;
    solve_weights(start);  // warm: the clusters kept from the last round start from their weights
    for (size_t j = 0; j < clusters.size(); ++j) clusters[cluster_at[j]].weight = weights_[j];
    parallel::for_each(static_cast<int>(normals.size()), kParallelMin,
                       [&](int k) { error[k] = std::abs(value(normals[k]) - 1.0); });
    max_input_error_ = *std::max_element(error.begin(), error.end());
    if (!(max_input_error_ > kTolerance)) break;
    // Split the clusters that have a normal off by more than the tolerance.
    std::vector<Cluster> refined;
    bool changed = false;
    for (Cluster& c : clusters) {
      double worst = 0;
      for (int k : c.members) worst = std::max(worst, error[k]);
      if (worst > kTolerance && c.members.size() > 1 && c.angle * 0.5 >= finest_angle * (1 - 1e-12)) {
        for (Cluster& sub : clusters_of(normals, c.members, c.angle * 0.5)) refined.push_back(std::move(sub));
        changed = true;
      } else {
        refined.push_back(std::move(c));
      }
    }
    if (!changed) break;
    // Refining adds nodes; beyond the memory cap keep the coarser set (its error is what it is).
    const double reach = std::min(1.0, (1.0 - cutoff_) / 2.0);  // share of the sphere within reach
    if (static_cast<double>(refined.size()) * refined.size() * reach > kMaxKernelEntries) break;
    clusters = std::move(refined);
  }
  double sum_abs = 0;
  for (double& w : weights_) {
    w *= scale;
    sum_abs += std::abs(w);
  }
  for (auto& t : terms_) t[9] *= scale;
  truncation_bound_ = cutoff_ > -1.0 ? kTruncation * sum_abs : 0.0;
}

std::vector<int> NormalField::build_grid() {
  // Cells a fraction of the reach of a term wide (chord sqrt(2 (1 - cutoff))); each cell that meets
  // the sphere lists every node within reach of any of its points, so x only reads its own cell's list.
  const double reach = cutoff_ > -1.0 ? std::sqrt(2.0 * (1.0 - cutoff_)) : 2.0;
  cells_ = std::clamp(static_cast<int>(std::ceil(2.0 * kCellsPerReach / reach)), 1, kMaxCellsPerAxis);
  cell_size_ = 2.0 / cells_;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * cell_size_;
  const int M = static_cast<int>(nodes_.size());
  // Nodes in the order of their own cell, for locality.
  std::vector<int> own(M), order(M);
  for (int j = 0; j < M; ++j) own[j] = cell_index(nodes_[j]);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return own[a] < own[b]; });
  std::vector<Vector3d> sorted(M);
  for (int j = 0; j < M; ++j) sorted[j] = nodes_[order[j]];
  nodes_ = std::move(sorted);
  terms_.resize(M);
  for (int j = 0; j < M; ++j) {
    const Vector3d& n = nodes_[j];
    terms_[j] = {n.x(), n.y(), n.z(), n.x() * n.x(), n.x() * n.y(), n.x() * n.z(), n.y() * n.y(),
                 n.y() * n.z(), n.z() * n.z(), 0.0};
  }
  // (cell, node) pairs, counted then filled: lists come out in node order.
  const double radius = reach + half_diagonal;
  auto coord = [&](double v) { return std::clamp(static_cast<int>(std::floor((v + 1.0) / cell_size_)), 0, cells_ - 1); };
  auto for_cells_of = [&](int j, auto&& f) {
    const Vector3d& m = nodes_[j];
    for (int z = coord(m.z() - radius); z <= coord(m.z() + radius); ++z)
      for (int y = coord(m.y() - radius); y <= coord(m.y() + radius); ++y)
        for (int x = coord(m.x() - radius); x <= coord(m.x() + radius); ++x) {
          const Vector3d c = (Vector3d(x, y, z) + Vector3d::Constant(0.5)) * cell_size_ - Vector3d::Ones();
          if (std::abs(c.norm() - 1.0) <= half_diagonal && (c - m).norm() <= radius) f(x + cells_ * (y + cells_ * z));
        }
  };
  list_start_.assign(static_cast<size_t>(cells_) * cells_ * cells_ + 1, 0);
  for (int j = 0; j < M; ++j) for_cells_of(j, [&](int c) { ++list_start_[c + 1]; });
  std::partial_sum(list_start_.begin(), list_start_.end(), list_start_.begin());
  list_.resize(list_start_.back());
  std::vector<int> fill(list_start_.begin(), list_start_.end() - 1);
  for (int j = 0; j < M; ++j) for_cells_of(j, [&](int c) { list_[fill[c]++] = j; });
  return order;
}

int NormalField::cell_index(const Vector3d& x) const {
  auto coord = [&](double v) { return std::clamp(static_cast<int>(std::floor((v + 1.0) / cell_size_)), 0, cells_ - 1); };
  return coord(x.x()) + cells_ * (coord(x.y()) + cells_ * coord(x.z()));
}

double NormalField::solve_weights(const std::vector<double>& start) {
  const int M = static_cast<int>(nodes_.size());
  // The truncated kernel matrix, row by row (CSR), from the same grid the evaluation uses.
  std::vector<std::vector<std::pair<int, double>>> rows(M);
  parallel::for_each(M, kParallelMin, [&](int i) {
    const int c = cell_index(nodes_[i]);
    for (int l = list_start_[c]; l < list_start_[c + 1]; ++l) {
      const int j = list_[l];
      const double t = nodes_[i].dot(nodes_[j]);
      if (t >= cutoff_) rows[i].emplace_back(j, std::exp(sigma_ * (t - 1.0)));
    }
  });
  auto multiply = [&](const std::vector<double>& v, std::vector<double>& out) {
    // Serial: hundreds of short loops back to back, where a pool's hand-offs would cost most.
    for (int i = 0; i < M; ++i) {
      double s = 0;
      for (const auto& [j, a] : rows[i]) s += a * v[j];
      out[i] = s + kRidge * v[i];
    }
  };
  // Preconditioned CG from Shepard's weights w = 1 / (row sum), which already give g ~ 1 on a
  // plateau; the preconditioner is the row sums too.
  std::vector<double> diag(M), w(M), r(M), z(M), p(M), q(M);
  for (int i = 0; i < M; ++i) {
    double s = 0;
    for (const auto& [j, a] : rows[i]) s += a;
    diag[i] = s;
    w[i] = std::isnan(start[i]) ? 1.0 / s : start[i];
  }
  multiply(w, q);
  double worst = 0;
  for (int i = 0; i < M; ++i) {
    r[i] = 1.0 - q[i];
    worst = std::max(worst, std::abs(r[i]));
  }
  double rho_old = 0;
  for (int it = 0; it < kMaxIterations && worst > kSolveTolerance; ++it) {
    double rho = 0;
    for (int i = 0; i < M; ++i) {
      z[i] = r[i] / diag[i];
      rho += r[i] * z[i];
    }
    const double beta = it == 0 ? 0.0 : rho / rho_old;
    for (int i = 0; i < M; ++i) p[i] = z[i] + beta * p[i];
    multiply(p, q);
    double pq = 0;
    for (int i = 0; i < M; ++i) pq += p[i] * q[i];
    if (!(pq > 0) || !std::isfinite(pq)) break;  // truncation made A indefinite: keep what we have
    const double alpha = rho / pq;
    worst = 0;
    for (int i = 0; i < M; ++i) {
      w[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      worst = std::max(worst, std::abs(r[i]));
    }
    rho_old = rho;
  }
  weights_ = w;
  for (int j = 0; j < M; ++j) terms_[j][9] = w[j];
  return worst;
}

void NormalField::accumulate(const Vector3d& x, double sums[10]) const {
  const double s = sigma_, cut = cutoff_;
  const int cell = cell_index(x);
  const int* list = list_.data();
  for (int l = list_start_[cell], end = list_start_[cell + 1]; l < end; ++l) {
    const std::array<double, 10>& t = terms_[list[l]];
    const double d = x.x() * t[0] + x.y() * t[1] + x.z() * t[2];
    if (d < cut) continue;
    const double c = t[9] * std::exp(s * (d - 1.0));
    sums[0] += c;
    for (int k = 0; k < 9; ++k) sums[k + 1] += c * t[k];
  }
}

double NormalField::value(const Vector3d& x) const {
  // g alone (the set-up's check at every input normal): one exponential per node within reach.
  const int cell = cell_index(x);
  double g = 0;
  for (int l = list_start_[cell], end = list_start_[cell + 1]; l < end; ++l) {
    const std::array<double, 10>& t = terms_[list_[l]];
    const double d = x.x() * t[0] + x.y() * t[1] + x.z() * t[2];
    if (d >= cutoff_) g += t[9] * std::exp(sigma_ * (d - 1.0));
  }
  return g;
}

}  // namespace gauss
