#include "gauss/cholesky_solver.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gauss {
namespace {

int max_threads() {
#ifdef _OPENMP
  return std::min(omp_get_max_threads(), 8);
#else
  return 1;
#endif
}

// s -= sum_k values[k] * y[idx[k]] for the three columns. Two independent accumulator sets halve the
// floating-point dependency chain; the pairing is fixed, so the result depends only on the data.
inline void subtract_gather(const int* idx, const double* values, int begin, int end, const double* y,
                            double& s0, double& s1, double& s2) {
  double a0 = 0, a1 = 0, a2 = 0, b0 = 0, b1 = 0, b2 = 0;
  int k = begin;
  for (; k + 1 < end; k += 2) {
    const double* r = y + 3 * idx[k];
    const double* t = y + 3 * idx[k + 1];
    const double l = values[k], m = values[k + 1];
    a0 += l * r[0];
    a1 += l * r[1];
    a2 += l * r[2];
    b0 += m * t[0];
    b1 += m * t[1];
    b2 += m * t[2];
  }
  if (k < end) {
    const double* r = y + 3 * idx[k];
    const double l = values[k];
    a0 += l * r[0];
    a1 += l * r[1];
    a2 += l * r[2];
  }
  s0 -= a0 + b0;
  s1 -= a1 + b1;
  s2 -= a2 + b2;
}

}  // namespace

void CholeskySolver::factor(const Eigen::SparseMatrix<double>& A) {
  n_ = static_cast<int>(A.rows());
  const int n = n_;
  // Fill-reducing ordering (approximate minimum degree on the pattern of A + A^T).
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  {
    Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int>()(full, amd);
  }
  perm_.assign(amd.indices().data(), amd.indices().data() + n);  // perm_[new] = old
  new_of_old_.assign(n, 0);
  for (int i = 0; i < n; ++i) new_of_old_[perm_[i]] = i;
  const std::vector<int>& new_of_old = new_of_old_;

  // The permuted matrix's upper triangle by columns: column k holds row k of the lower triangle.
  std::vector<int> up_start(n + 1, 0), up_rows;
  std::vector<double> up_values;
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) ++up_start[std::max(new_of_old[it.row()], new_of_old[j]) + 1];
  for (int k = 0; k < n; ++k) up_start[k + 1] += up_start[k];
  up_rows.resize(up_start[n]);
  up_values.resize(up_start[n]);
  {
    std::vector<int> fill(up_start.begin(), up_start.end() - 1);
    for (int j = 0; j < n; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
        if (it.row() >= j) {
          const int a = new_of_old[it.row()], b = new_of_old[j];
          const int slot = fill[std::max(a, b)]++;
          up_rows[slot] = std::min(a, b);
          up_values[slot] = it.value();
        }
  }

  // Symbolic factorization (up-looking): the elimination tree and the column counts of L. Row k of
  // L has an entry in column i for every i on the tree paths from the entries of row k up to k.
  std::vector<int> parent(n, -1), flag(n, -1), col_count(n, 0), row_count(n, 0);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = up_start[k]; p < up_start[k + 1]; ++p)
      for (int i = up_rows[p]; flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++col_count[i];
        ++row_count[k];
        flag[i] = k;
      }
  }
  col_start_.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) col_start_[j + 1] = col_start_[j] + col_count[j];
  col_rows_.assign(col_start_[n], 0);
  col_values_.assign(col_start_[n], 0.0);
  std::vector<double> work(n);
  for (int j = 0; j < n; ++j) work[j] = 1.0 + col_count[j] + row_count[j];
  partition_elimination_tree(parent, work, max_threads());

  // Numeric factorization (up-looking LDL^T). Rows of disjoint subtrees write disjoint columns and
  // read only their own subtree, so each thread factors its part; the rows above the cut follow.
  std::vector<int> fill_count(n, 0);  // entries written so far in each column
  std::vector<double> D(n, 0.0);
  bool ok = true;
  auto factor_rows = [&](const std::vector<int>& rows, std::vector<double>& Y, std::vector<int>& mark,
                         std::vector<int>& pattern) {
    for (int k : rows) {
      int top = n;
      mark[k] = k;
      for (int p = up_start[k]; p < up_start[k + 1]; ++p) {
        int i = up_rows[p];
        Y[i] += up_values[p];
        int len = 0;
        for (; mark[i] != k; i = parent[i]) {
          pattern[len++] = i;
          mark[i] = k;
        }
        while (len > 0) pattern[--top] = pattern[--len];
      }
      double d = Y[k];
      Y[k] = 0.0;
      for (; top < n; ++top) {
        const int i = pattern[top];
        const double yi = Y[i];
        Y[i] = 0.0;
        const int begin = col_start_[i], end = begin + fill_count[i];
        for (int p = begin; p < end; ++p) Y[col_rows_[p]] -= col_values_[p] * yi;
        const double l = yi / D[i];
        d -= l * yi;
        col_rows_[end] = k;
        col_values_[end] = l;
        ++fill_count[i];
      }
      D[k] = d;
      if (!(d > 0) || !std::isfinite(d)) ok = false;
    }
  };
  const int parts = static_cast<int>(parallel_rows_.size());
#pragma omp parallel if (parts > 1 && n > 4096) num_threads(parts)
  {
    std::vector<double> Y(n, 0.0);
    std::vector<int> mark(n, -1), pattern(n);
#pragma omp for schedule(static, 1)
    for (int t = 0; t < parts; ++t) factor_rows(parallel_rows_[t], Y, mark, pattern);
  }
  {
    std::vector<double> Y(n, 0.0);
    std::vector<int> mark(n, -1), pattern(n);
    factor_rows(top_rows_, Y, mark, pattern);
  }
  if (!ok)
    throw std::runtime_error("the mesh's Laplacian is not positive definite (the mesh is too degenerate to solve)");
  inv_diag_.resize(n);
  for (int i = 0; i < n; ++i) inv_diag_[i] = 1.0 / D[i];

  // The same factor by rows, for the forward sweep.
  row_start_.assign(n + 1, 0);
  for (int p = 0; p < col_start_[n]; ++p) ++row_start_[col_rows_[p] + 1];
  for (int i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  row_cols_.resize(col_rows_.size());
  row_values_.resize(col_values_.size());
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  for (int j = 0; j < n; ++j)  // columns in increasing order: each row's entries come out sorted
    for (int p = col_start_[j]; p < col_start_[j + 1]; ++p) {
      const int slot = fill[col_rows_[p]]++;
      row_cols_[slot] = j;
      row_values_[slot] = col_values_[p];
    }
}

void CholeskySolver::partition_elimination_tree(const std::vector<int>& parent, const std::vector<double>& work,
                                                int parts) {
  const int n = n_;
  parallel_rows_.assign(std::max(parts, 1), {});
  top_rows_.clear();
  std::vector<int> child_start(n + 1, 0), children(n);
  std::vector<double> subtree(work);
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) {
      subtree[parent[j]] += subtree[j];  // parent[j] > j: children are complete first
      ++child_start[parent[j] + 1];
    }
  for (int j = 0; j < n; ++j) child_start[j + 1] += child_start[j];
  {
    std::vector<int> fill(child_start.begin(), child_start.end() - 1);
    for (int j = 0; j < n; ++j)
      if (parent[j] >= 0) children[fill[parent[j]]++] = j;
  }
  double total = 0;
  for (int j = 0; j < n; ++j)
    if (parent[j] < 0) total += subtree[j];
  const int P = static_cast<int>(parallel_rows_.size());

  // Cut the heaviest subtree's root off, step by step, estimating the time of each cut as the rows
  // above it plus max(heaviest subtree, even share); keep the best number of steps. Trees with a long
  // chain on top need many steps before they fork.
  auto heavier = [&](int a, int b) { return subtree[a] != subtree[b] ? subtree[a] < subtree[b] : a > b; };
  auto run = [&](int steps, std::vector<int>* cut) {
    std::priority_queue<int, std::vector<int>, decltype(heavier)> heap(heavier);
    for (int j = 0; j < n; ++j)
      if (parent[j] < 0) heap.push(j);
    double top = 0, best = 2 * total;
    int best_steps = 0;
    for (int s = 0; !heap.empty(); ++s) {
      const double estimate = top + std::max(subtree[heap.top()], (total - top) / P);
      if (estimate < best) {
        best = estimate;
        best_steps = s;
      }
      if (s == steps || P == 1 || top > 0.5 * total || estimate <= 1.02 * total / P) break;
      const int r = heap.top();
      heap.pop();
      top += work[r];
      if (cut) cut->push_back(r);
      for (int k = child_start[r]; k < child_start[r + 1]; ++k) heap.push(children[k]);
    }
    std::vector<int> roots;
    while (!heap.empty()) {
      roots.push_back(heap.top());
      heap.pop();
    }
    return std::make_pair(best_steps, roots);
  };
  const int steps = run(-1, nullptr).first;
  std::vector<int> roots = run(steps, &top_rows_).second;  // heaviest first
  // Longest-processing-time packing of the remaining subtrees into the parts.
  std::vector<double> load(P, 0.0);
  std::vector<int> stack;
  for (int r : roots) {
    const int bin = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[bin] += subtree[r];
    stack.assign(1, r);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      parallel_rows_[bin].push_back(v);
      for (int k = child_start[v]; k < child_start[v + 1]; ++k) stack.push_back(children[k]);
    }
  }
  for (auto& rows : parallel_rows_) std::sort(rows.begin(), rows.end());
  std::sort(top_rows_.begin(), top_rows_.end());
}

void CholeskySolver::solve_in_place(double* B, double* y) const {
  for (int i = 0; i < n_; ++i)
    for (int c = 0; c < 3; ++c) y[3 * i + c] = B[3 * perm_[i] + c];
  solve_ordered_in_place(y);
  for (int i = 0; i < n_; ++i)
    for (int c = 0; c < 3; ++c) B[3 * perm_[i] + c] = y[3 * i + c];
}

void CholeskySolver::solve_ordered_in_place(double* y) const {
  auto forward_row = [&](int i) {
    double s0 = y[3 * i], s1 = y[3 * i + 1], s2 = y[3 * i + 2];
    subtract_gather(row_cols_.data(), row_values_.data(), row_start_[i], row_start_[i + 1], y, s0, s1, s2);
    y[3 * i] = s0;
    y[3 * i + 1] = s1;
    y[3 * i + 2] = s2;
  };
  auto backward_row = [&](int j) {
    double s0 = y[3 * j] * inv_diag_[j], s1 = y[3 * j + 1] * inv_diag_[j], s2 = y[3 * j + 2] * inv_diag_[j];
    subtract_gather(col_rows_.data(), col_values_.data(), col_start_[j], col_start_[j + 1], y, s0, s1, s2);
    y[3 * j] = s0;
    y[3 * j + 1] = s1;
    y[3 * j + 2] = s2;
  };
  const int parts = static_cast<int>(parallel_rows_.size());
  // Forward (L y = b): the subtrees, one part per thread, then the rows above the cut.
#pragma omp parallel for schedule(static, 1) if (parts > 1 && n_ > 4096)
  for (int t = 0; t < parts; ++t)
    for (int i : parallel_rows_[t]) forward_row(i);
  for (int i : top_rows_) forward_row(i);
  // Backward (D L^T x = y): the rows above the cut first, then the subtrees; every row a row reads
  // lies above it in the tree and is final by then.
  for (auto it = top_rows_.rbegin(); it != top_rows_.rend(); ++it) backward_row(*it);
#pragma omp parallel for schedule(static, 1) if (parts > 1 && n_ > 4096)
  for (int t = 0; t < parts; ++t)
    for (auto it = parallel_rows_[t].rbegin(); it != parallel_rows_[t].rend(); ++it) backward_row(*it);
}

}  // namespace gauss
