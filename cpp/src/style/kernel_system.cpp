#include "gauss/style/kernel_system.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gauss/util/parallel.h"

namespace gauss {
namespace {

using Eigen::Vector3d;

// Sums over nodes are split into chunks of this many, fixed whatever the thread count, and the
// chunks' sums are added in order: the same bits on one thread or many.
constexpr int kChunk = 1024;
constexpr int kParallelMin = 2048;

// sum_i f(i) over [0, n) in fixed chunks; `partial` is scratch space.
template <class F>
double ordered_sum(int n, std::vector<double>& partial, F&& f) {
  const int chunks = (n + kChunk - 1) / kChunk;
  partial.assign(chunks, 0.0);
  parallel::for_each(chunks, 2, [&](int c) {
    double s = 0;
    for (int i = c * kChunk, end = std::min(n, (c + 1) * kChunk); i < end; ++i) s += f(i);
    partial[c] = s;
  });
  double total = 0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace

KernelSystem::KernelSystem(const std::vector<Vector3d>& nodes, double sigma, double cutoff, double ridge,
                           const NodeGrid& grid, const std::vector<std::vector<int>>& patches)
    : ridge_(ridge) {
  if (!(sigma > 0) || !(ridge > 0)) throw std::invalid_argument("KernelSystem needs sigma > 0 and ridge > 0");
  const int M = static_cast<int>(nodes.size());
  // Rows: each node's grid list filtered by the cutoff. Counted in parallel, then filled.
  std::vector<int> count(M);
  parallel::for_each(M, kParallelMin, [&](int i) {
    const int c = grid.cell(nodes[i]);
    int n = 0;
    for (const int* j = grid.begin(c); j != grid.end(c); ++j) n += nodes[i].dot(nodes[*j]) >= cutoff;
    count[i] = n;
  });
  row_start_.assign(M + 1, 0);
  for (int i = 0; i < M; ++i) row_start_[i + 1] = row_start_[i] + count[i];
  cols_.resize(row_start_[M]);
  values_.resize(row_start_[M]);
  parallel::for_each(M, kParallelMin, [&](int i) {
    const int c = grid.cell(nodes[i]);
    size_t k = row_start_[i];
    for (const int* j = grid.begin(c); j != grid.end(c); ++j) {
      const double t = nodes[i].dot(nodes[*j]);
      if (t >= cutoff) {
        cols_[k] = *j;
        values_[k++] = std::exp(sigma * (t - 1.0));
      }
    }
  });

  // Patches: the dense matrix A_PP + ridge I of each, inverted in place.
  patch_start_.assign(1, 0);
  factor_start_.assign(1, 0);
  for (const std::vector<int>& p : patches) {
    const size_t size = std::min<size_t>(p.size(), kMaxPatch);
    patch_nodes_.insert(patch_nodes_.end(), p.begin(), p.begin() + size);
    patch_start_.push_back(patch_nodes_.size());
    factor_start_.push_back(factor_start_.back() + size * size);
  }
  const int P = static_cast<int>(patches.size());
  factors_.assign(factor_start_.back(), 0.0);
  std::vector<char> usable(P, 0);
  parallel::for_each(P, 64, [&](int p) {
    const int b = static_cast<int>(patch_start_[p + 1] - patch_start_[p]);
    const int* idx = patch_nodes_.data() + patch_start_[p];
    Eigen::Map<Eigen::MatrixXd> m(factors_.data() + factor_start_[p], b, b);
    for (int x = 0; x < b; ++x)
      for (int y = 0; y <= x; ++y) {
        const double t = nodes[idx[x]].dot(nodes[idx[y]]);
        m(x, y) = m(y, x) = (t >= cutoff ? std::exp(sigma * (t - 1.0)) : 0.0) + (x == y ? ridge : 0.0);
      }
    // Stored as the inverse: applying it is then a dense product whose columns vectorize, where the
    // two triangular solves of a Cholesky factor run one long dependency chain (measured:
    // docs/performance.md#figures-behind-the-codes-choices). With the ridge the block's condition
    // number stays below ~1e4: the inverse is accurate.
    const Eigen::LLT<Eigen::MatrixXd> llt(m);
    usable[p] = llt.info() == Eigen::Success;
    if (usable[p]) m = llt.solve(Eigen::MatrixXd::Identity(b, b));
  });
  // An unusable patch (not positive definite in floating point) is skipped; a node in no usable patch
  // is preconditioned by its diagonal.
  usable_ = std::move(usable);
  covered_.assign(M, 0);
  for (int p = 0; p < P; ++p)
    if (usable_[p])
      for (size_t l = patch_start_[p]; l < patch_start_[p + 1]; ++l) covered_[patch_nodes_[l]] = 1;
  patch_values_.assign(patch_nodes_.size(), 0.0);
}

void KernelSystem::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  parallel::for_each(size(), kParallelMin, [&](int i) {
    double s = 0;
    for (size_t k = row_start_[i]; k < row_start_[i + 1]; ++k) s += values_[k] * x[cols_[k]];
    y[i] = s + ridge_ * x[i];
  });
}

void KernelSystem::precondition(const std::vector<double>& r, std::vector<double>& z) {
  // Each patch solves its block for its share of r (in parallel, into its own slice of
  // patch_values_); the shares are then added in patch order.
  const int P = static_cast<int>(usable_.size());
  parallel::for_each(P, 64, [&](int p) {
    if (!usable_[p]) return;
    const int b = static_cast<int>(patch_start_[p + 1] - patch_start_[p]);
    const int* idx = patch_nodes_.data() + patch_start_[p];
    const double* inverse = factors_.data() + factor_start_[p];  // column-major
    double rp[kMaxPatch];
    for (int x = 0; x < b; ++x) rp[x] = r[idx[x]];
    double* u = patch_values_.data() + patch_start_[p];
    std::fill(u, u + b, 0.0);
    for (int y = 0; y < b; ++y) {
      const double* column = inverse + static_cast<size_t>(y) * b;
      for (int x = 0; x < b; ++x) u[x] += column[x] * rp[y];
    }
  });
  for (int i = 0; i < size(); ++i) z[i] = covered_[i] ? 0.0 : r[i] / (1.0 + ridge_);
  for (int p = 0; p < P; ++p)
    if (usable_[p])
      for (size_t l = patch_start_[p]; l < patch_start_[p + 1]; ++l) z[patch_nodes_[l]] += patch_values_[l];
}

std::vector<double> KernelSystem::shepard() const {
  std::vector<double> w(size());
  parallel::for_each(size(), kParallelMin, [&](int i) {
    double s = ridge_;
    for (size_t k = row_start_[i]; k < row_start_[i + 1]; ++k) s += values_[k];
    w[i] = 1.0 / s;
  });
  return w;
}

double KernelSystem::solve(std::vector<double>& w, const std::vector<double>& b, double tolerance,
                           int max_iterations) {
  const int M = size();
  if (static_cast<int>(w.size()) != M || (!b.empty() && static_cast<int>(b.size()) != M))
    throw std::invalid_argument("KernelSystem::solve: one start value (and right-hand side) per node");
  auto rhs = [&](int i) { return b.empty() ? 1.0 : b[i]; };
  std::vector<double> r(M), z(M), p(M), q(M), partial;
  auto largest = [&](const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, std::abs(x));  // a max: the same in any order
    return m;
  };
  multiply(w, q);
  for (int i = 0; i < M; ++i) r[i] = rhs(i) - q[i];
  iterations_ = 0;
  if (largest(r) > tolerance) {
    precondition(r, z);
    p = z;
    double rz = ordered_sum(M, partial, [&](int i) { return r[i] * z[i]; });
    for (; iterations_ < max_iterations; ++iterations_) {
      multiply(p, q);
      const double pq = ordered_sum(M, partial, [&](int i) { return p[i] * q[i]; });
      if (!(pq > 0) || !std::isfinite(pq)) break;  // rounding made the search direction useless: stop
      const double alpha = rz / pq;
      for (int i = 0; i < M; ++i) {
        w[i] += alpha * p[i];
        r[i] -= alpha * q[i];
      }
      if (largest(r) <= tolerance) {
        ++iterations_;
        break;
      }
      precondition(r, z);
      const double rz_next = ordered_sum(M, partial, [&](int i) { return r[i] * z[i]; });
      const double beta = rz_next / rz;
      rz = rz_next;
      for (int i = 0; i < M; ++i) p[i] = z[i] + beta * p[i];
    }
  }
  multiply(w, q);  // the true residual: CG's running one drifts by rounding
  for (int i = 0; i < M; ++i) r[i] = rhs(i) - q[i];
  return largest(r);
}

}  // namespace gauss
