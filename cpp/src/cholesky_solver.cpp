#include "gauss/cholesky_solver.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

#include "gauss/parallel.h"

namespace gauss {
namespace {

// The tree is always cut into this many parts, whatever the number of threads: the cut decides the
// row numbering and with it the rounding, and results must not depend on the thread count (nor on
// the machine). Two parts suit the 2-core target; more cores still speed up the other phases.
constexpr int kParts = 2;

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

namespace {

// The permuted matrix's upper triangle by columns (column k holds row k of the lower triangle), for
// the up-looking factorization. A: lower triangle, caller's numbering; new_of_old: the ordering.
void permuted_upper(const Eigen::SparseMatrix<double>& A, const std::vector<int>& new_of_old,
                    std::vector<int>& start, std::vector<int>& rows, std::vector<double>& values) {
  const int n = static_cast<int>(A.rows());
  start.assign(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) ++start[std::max(new_of_old[it.row()], new_of_old[j]) + 1];
  for (int k = 0; k < n; ++k) start[k + 1] += start[k];
  rows.resize(start[n]);
  values.resize(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) {
        const int a = new_of_old[it.row()], b = new_of_old[j];
        const int slot = fill[std::max(a, b)]++;
        rows[slot] = std::min(a, b);
        values[slot] = it.value();
      }
}

// Symbolic up-looking factorization: the elimination tree and the row and column counts of L.
// Row k of L has an entry in column i for every i on the tree paths from row k's entries up to k.
void elimination_tree(int n, const std::vector<int>& start, const std::vector<int>& rows, std::vector<int>& parent,
                      std::vector<int>& col_count, std::vector<int>& row_count) {
  parent.assign(n, -1);
  col_count.assign(n, 0);
  row_count.assign(n, 0);
  std::vector<int> flag(n, -1);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = start[k]; p < start[k + 1]; ++p)
      for (int i = rows[p]; flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++col_count[i];
        ++row_count[k];
        flag[i] = k;
      }
  }
}

}  // namespace

void CholeskySolver::factor(const Eigen::SparseMatrix<double>& A) {
  n_ = static_cast<int>(A.rows());
  const int n = n_;
  // 1. Fill-reducing ordering (approximate minimum degree on the pattern of A + A^T).
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  {
    Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int>()(full, amd);
  }
  std::vector<int> amd_new_of_old(n);
  for (int i = 0; i < n; ++i) amd_new_of_old[amd.indices()[i]] = i;
  std::vector<int> up_start, up_rows, parent, col_count, row_count;
  std::vector<double> up_values;
  permuted_upper(A, amd_new_of_old, up_start, up_rows, up_values);
  elimination_tree(n, up_start, up_rows, parent, col_count, row_count);

  // 2. Cut the tree into one group of subtrees per thread plus the rows above the cut, and number
  // the rows group by group: each thread then owns a contiguous range of rows and of L's columns
  // (no two threads write the same cache lines), and the order is still a topological order of
  // the tree, so L has exactly the same fill.
  std::vector<double> work(n);
  for (int j = 0; j < n; ++j) work[j] = 1.0 + col_count[j] + row_count[j];
  std::vector<std::vector<int>> groups = partition_elimination_tree(parent, work, kParts);
  part_start_.assign(1, 0);
  std::vector<int> sequence;
  for (const std::vector<int>& g : groups) {
    sequence.insert(sequence.end(), g.begin(), g.end());
    part_start_.push_back(static_cast<int>(sequence.size()));
  }
  part_start_.pop_back();  // the last group is the rows above the cut: [part_start_.back(), n)
  new_of_old_.resize(n);
  for (int i = 0; i < n; ++i) new_of_old_[amd.indices()[sequence[i]]] = i;
  permuted_upper(A, new_of_old_, up_start, up_rows, up_values);
  elimination_tree(n, up_start, up_rows, parent, col_count, row_count);
  col_start_.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) col_start_[j + 1] = col_start_[j] + col_count[j];
  col_rows_.assign(col_start_[n], 0);
  col_values_.assign(col_start_[n], 0.0);

  // 3. Numeric factorization (up-looking LDL^T). Rows of a thread's subtrees read and write only
  // that thread's columns; the rows above the cut follow on one thread.
  std::vector<int> fill_count(n, 0);  // entries written so far in each column
  std::vector<double> D(n, 0.0);
  int failed = 0;
  auto factor_rows = [&](int first, int last, std::vector<double>& Y, std::vector<int>& mark,
                         std::vector<int>& pattern) {
    int bad = 0;
    for (int k = first; k < last; ++k) {
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
      bad += !(d > 0) || !std::isfinite(d);
    }
    return bad;
  };
  const int parts = static_cast<int>(part_start_.size()) - 1;
  std::vector<int> part_failed(parts, 0);
  parallel::for_tasks(parts, n > 4096, [&](int t) {
    std::vector<double> Y(n, 0.0);
    std::vector<int> mark(n, -1), pattern(n);
    part_failed[t] = factor_rows(part_start_[t], part_start_[t + 1], Y, mark, pattern);
  });
  for (int f : part_failed) failed += f;
  {
    std::vector<double> Y(n, 0.0);
    std::vector<int> mark(n, -1), pattern(n);
    failed += factor_rows(part_start_.back(), n, Y, mark, pattern);
  }
  if (failed)
    throw std::runtime_error("the mesh's Laplacian is not positive definite (the mesh is too degenerate to solve)");
  inv_diag_.resize(n);
  for (int i = 0; i < n; ++i) inv_diag_[i] = 1.0 / D[i];

  // 4. The same factor by rows, for the forward sweep. A row of a part only has entries in that
  // part's columns, so the parts fill their rows in parallel; the rows above the cut come last.
  row_start_.assign(n + 1, 0);
  for (int p = 0; p < col_start_[n]; ++p) ++row_start_[col_rows_[p] + 1];
  for (int i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  row_cols_.resize(col_rows_.size());
  row_values_.resize(col_values_.size());
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  const int top_begin = part_start_.back();
  auto fill_rows = [&](int first_col, int last_col, int first_row, int last_row) {
    for (int j = first_col; j < last_col; ++j)  // increasing columns: each row comes out sorted
      for (int p = col_start_[j]; p < col_start_[j + 1]; ++p) {
        const int i = col_rows_[p];
        if (i < first_row || i >= last_row) continue;
        const int slot = fill[i]++;
        row_cols_[slot] = j;
        row_values_[slot] = col_values_[p];
      }
  };
  parallel::for_tasks(parts, n > 4096, [&](int t) {
    fill_rows(part_start_[t], part_start_[t + 1], part_start_[t], part_start_[t + 1]);
  });
  fill_rows(0, n, top_begin, n);
}

std::vector<std::vector<int>> CholeskySolver::partition_elimination_tree(const std::vector<int>& parent,
                                                                         const std::vector<double>& work,
                                                                         int parts) const {
  const int n = n_;
  const int P = std::max(parts, 1);
  std::vector<std::vector<int>> groups(P + 1);  // P parts, then the rows above the cut
  std::vector<int>& top_rows = groups[P];
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
  std::vector<int> roots = run(steps, &top_rows).second;  // heaviest first
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
      groups[bin].push_back(v);
      for (int k = child_start[v]; k < child_start[v + 1]; ++k) stack.push_back(children[k]);
    }
  }
  for (auto& g : groups) std::sort(g.begin(), g.end());  // ascending: a topological order
  return groups;
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
  const int parts = static_cast<int>(part_start_.size()) - 1;
  // Forward (L y = b): the subtrees, one range per thread, then the rows above the cut.
  parallel::for_tasks(parts, n_ > 4096, [&](int t) {
    for (int i = part_start_[t]; i < part_start_[t + 1]; ++i) forward_row(i);
  });
  for (int i = part_start_.back(); i < n_; ++i) forward_row(i);
  // Backward (D L^T x = y): the rows above the cut first, then the subtrees; every row a row reads
  // lies above it in the tree and is final by then.
  for (int j = n_ - 1; j >= part_start_.back(); --j) backward_row(j);
  parallel::for_tasks(parts, n_ > 4096, [&](int t) {
    for (int j = part_start_[t + 1] - 1; j >= part_start_[t]; --j) backward_row(j);
  });
}

}  // namespace gauss
