#include "gauss/sparse/cholesky_solver.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "gauss/util/memory_budget.h"
#include "gauss/sparse/nested_dissection.h"
#include "gauss/util/parallel.h"
#include "gauss/sparse/supernodal_analysis.h"
#include "gauss/sparse/supernodal_factor.h"
#include "gauss/util/system_memory.h"

namespace gauss {
namespace {

// s -= sum_k u[k] * y[3k..3k+2] for the three columns, u contiguous. Two accumulator sets halve the
// floating-point dependency chain; the pairing is fixed, so the result depends only on the data.
template <class T>
inline void subtract_dot(const T* u, const double* y, int len, double& s0, double& s1, double& s2) {
  double a0 = 0, a1 = 0, a2 = 0, b0 = 0, b1 = 0, b2 = 0;
  int k = 0;
  for (; k + 1 < len; k += 2) {
    const double l = u[k], m = u[k + 1];
    a0 += l * y[3 * k];
    a1 += l * y[3 * k + 1];
    a2 += l * y[3 * k + 2];
    b0 += m * y[3 * k + 3];
    b1 += m * y[3 * k + 4];
    b2 += m * y[3 * k + 5];
  }
  if (k < len) {
    const double l = u[k];
    a0 += l * y[3 * k];
    a1 += l * y[3 * k + 1];
    a2 += l * y[3 * k + 2];
  }
  s0 -= a0 + b0;
  s1 -= a1 + b1;
  s2 -= a2 + b2;
}

// The graph of A's off-diagonal entries, both directions, for the ordering.
void adjacency(const Eigen::SparseMatrix<double>& A, std::vector<int>& start, std::vector<int>& adj) {
  const int n = static_cast<int>(A.rows());
  start.assign(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() > j) {
        ++start[it.row() + 1];
        ++start[j + 1];
      }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  adj.resize(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() > j) {
        adj[fill[it.row()]++] = j;
        adj[fill[j]++] = static_cast<int>(it.row());
      }
}

// The count doubles of `values` rounded to floats in the same block, whose second half is then
// given back. Ascending and one at a time: float i ends at byte 4i + 4 <= 8i for i >= 1, so it never
// lands on a double not yet read (memcpy: the bytes change type under the pointers).
std::unique_ptr<float[], FreeDeleter> round_to_floats(FactorValues values, int64_t count) {
  unsigned char* bytes = reinterpret_cast<unsigned char*>(values.get());
  for (int64_t i = 0; i < count; ++i) {
    double d;
    std::memcpy(&d, bytes + sizeof(double) * i, sizeof d);
    const float f = static_cast<float>(d);
    std::memcpy(bytes + sizeof(float) * i, &f, sizeof f);
  }
  void* block = values.release();
  // A failed shrink leaves the block as it was: the floats are in its first half either way.
  if (void* shrunk = std::realloc(block, sizeof(float) * std::max<int64_t>(count, 1))) block = shrunk;
  return std::unique_ptr<float[], FreeDeleter>(static_cast<float*>(block));
}

// Values of L a supernode of w columns and m rows holds: its rows below the diagonal block, and
// the block's lower triangle.
int64_t supernode_nonzeros(int w, int m) { return int64_t{w} * m - int64_t{w} * (w - 1) / 2; }

}  // namespace

void CholeskySolver::factor(Eigen::SparseMatrix<double> A, Progress* watcher, Precision precision) {
  Progress unwatched;
  Progress& progress = watcher ? *watcher : unwatched;
  const bool own_run = !progress.running();
  if (own_run) progress.start(SetupPhase::ordering);
  const int n = static_cast<int>(A.rows());
  try {
    progress.enter(SetupPhase::ordering);
    std::vector<int> order;
    {
      std::vector<int> start, adj;
      adjacency(A, start, adj);
      order = nested_dissection(n, start, adj, progress);
    }
    progress.enter(SetupPhase::symbolic);
    SupernodalStructure S = analyse_supernodal(A, order, progress);
    Eigen::SparseMatrix<double>().swap(A);  // S.A has the values now
    // The ordering's scratch (much of it in the pool threads' arenas) and the analysis's, freed but
    // still resident, would lie under the factor: the set-up's peak.
    release_free_memory();
    check_memory(S.numeric_bytes(), "the factorization of " + std::to_string(n) + " unknowns");
    progress.enter(SetupPhase::factorizing);
    FactorValues values = factor_supernodal(S, progress);
    const int64_t num_values = S.num_values();

    const bool single = precision == Precision::single_values ||
                        (precision == Precision::automatic && n >= kSinglePrecisionUnknowns);

    // Everything succeeded: only now replace the previous factor.
    std::vector<double> inv_diag(n);
    long long nonzeros = 0;
    for (int s = 0; s < S.num_supernodes(); ++s) {
      const int f = S.col_start[s], w = S.col_start[s + 1] - f, m = S.row_start[s + 1] - S.row_start[s];
      const double* U = values.get() + S.value_start[s];
      for (int k = 0; k < w; ++k) inv_diag[f + k] = 1.0 / U[k + int64_t{w} * k];
      nonzeros += supernode_nonzeros(w, m);
    }
    std::vector<double> top_sums(3 * static_cast<size_t>(kFactorParts) * (n - S.top_col), 0.0);
    // The elimination tree of the supernodes: a supernode's parent holds its first row below the
    // diagonal block.
    std::vector<int> super_of_col(n), super_parent(S.num_supernodes(), -1);
    for (int t = 0; t < S.num_supernodes(); ++t)
      for (int c = S.col_start[t]; c < S.col_start[t + 1]; ++c) super_of_col[c] = t;
    for (int t = 0; t < S.num_supernodes(); ++t) {
      const int w = S.col_start[t + 1] - S.col_start[t];
      if (S.row_start[t + 1] - S.row_start[t] > w) super_parent[t] = super_of_col[S.rows[S.row_start[t] + w]];
    }
    n_ = n;
    nonzeros_ = nonzeros;
    new_of_old_ = std::move(S.new_of_old);
    col_start_ = std::move(S.col_start);
    row_start_ = std::move(S.row_start);
    rows_ = std::move(S.rows);
    value_start_ = std::move(S.value_start);
    inv_diag_ = std::move(inv_diag);
    if (single) {
      values_.reset();
      values_single_ = round_to_floats(std::move(values), num_values);
      a_start_ = std::move(S.A.start);
      a_rows_ = std::move(S.A.rows);
      a_values_ = std::move(S.A.values);
      refine_.assign(3 * static_cast<size_t>(n), 0.0);
    } else {
      values_ = std::move(values);
      values_single_.reset();
      a_start_ = {}, a_rows_ = {}, a_values_ = {}, refine_ = {};
    }
    part_start_ = std::move(S.part_start);
    top_col_ = S.top_col;
    top_sums_ = std::move(top_sums);
    super_of_col_ = std::move(super_of_col);
    super_parent_ = std::move(super_parent);
    plan_mark_.assign(super_parent_.size(), 0);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("not enough memory to factor the Laplacian of " + std::to_string(n) + " unknowns");
  }
  release_free_memory();  // the structure's scratch and the copy of A, before the caller's step buffers
  if (own_run) progress.finish();
}

template <class T>
void CholeskySolver::forward(const T* values, int first_super, int last_super, double* y, double* top_sums) const {
  for (int s = first_super; s < last_super; ++s) {
    const int f = col_start_[s], w = col_start_[s + 1] - f, m = row_start_[s + 1] - row_start_[s];
    const int* R = rows_.data() + row_start_[s];
    const T* U = values + value_start_[s];
    double* yJ = y + 3 * static_cast<size_t>(f);
    // Diagonal block: L_JJ z_J = y_J; column k of U holds row k of L_JJ left of the diagonal.
    for (int k = 0; k < w; ++k) {
      double s0 = yJ[3 * k], s1 = yJ[3 * k + 1], s2 = yJ[3 * k + 2];
      subtract_dot(U + int64_t{w} * k, yJ, k, s0, s1, s2);
      const double d = inv_diag_[f + k];
      yJ[3 * k] = s0 * d;
      yJ[3 * k + 1] = s1 * d;
      yJ[3 * k + 2] = s2 * d;
    }
    // Rows below: y_r -= L(r, J) z_J, or owed to a row above the cut (top_sums, added later).
    for (int c = w; c < m; ++c) {
      const int r = R[c];
      double s0 = 0, s1 = 0, s2 = 0;  // -L(r, J) z_J
      subtract_dot(U + int64_t{w} * c, yJ, w, s0, s1, s2);
      if (top_sums && r >= top_col_) {
        double* owed = top_sums + 3 * static_cast<size_t>(r - top_col_);
        owed[0] -= s0;
        owed[1] -= s1;
        owed[2] -= s2;
      } else {
        double* target = y + 3 * static_cast<size_t>(r);
        target[0] += s0;
        target[1] += s1;
        target[2] += s2;
      }
    }
  }
}

template <class T>
void CholeskySolver::backward(const T* values, int first_super, int last_super, double* y) const {
  for (int s = last_super - 1; s >= first_super; --s) {
    const int f = col_start_[s], w = col_start_[s + 1] - f, m = row_start_[s + 1] - row_start_[s];
    const int* R = rows_.data() + row_start_[s];
    const T* U = values + value_start_[s];
    double* yJ = y + 3 * static_cast<size_t>(f);
    // y_J -= L(R, J)^T x_R: the rows below are final (they lie above in the tree). Last row first,
    // so that the whole backward sweep reads the factor in one descending stream (the hardware
    // prefetcher follows it; block by block ascending it missed at every small supernode). Four rows
    // at a time, so y_J is loaded and stored once per four columns of U; the x values are copied
    // to locals because the compiler cannot know they do not alias y_J.
    int c = m;
    for (; c - 4 >= w; c -= 4) {
      double x[4][3];
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 3; ++i) x[j][i] = y[3 * static_cast<size_t>(R[c - 4 + j]) + i];
      const T* u0 = U + int64_t{w} * (c - 4);
      const T* u1 = u0 + w;
      const T* u2 = u1 + w;
      const T* u3 = u2 + w;
      for (int k = 0; k < w; ++k) {
        const double a = u0[k], b = u1[k], d = u2[k], e = u3[k];
        for (int i = 0; i < 3; ++i) yJ[3 * k + i] -= (a * x[0][i] + b * x[1][i]) + (d * x[2][i] + e * x[3][i]);
      }
    }
    for (--c; c >= w; --c) {
      const double* xr = y + 3 * static_cast<size_t>(R[c]);
      const double x0 = xr[0], x1 = xr[1], x2 = xr[2];
      const T* u = U + int64_t{w} * c;
      for (int k = 0; k < w; ++k) {
        yJ[3 * k] -= u[k] * x0;
        yJ[3 * k + 1] -= u[k] * x1;
        yJ[3 * k + 2] -= u[k] * x2;
      }
    }
    // Diagonal block: L_JJ^T x_J = y_J, last unknown first, by columns of U (contiguous).
    for (int k = w - 1; k >= 0; --k) {
      const double d = inv_diag_[f + k];
      const double x0 = yJ[3 * k] * d, x1 = yJ[3 * k + 1] * d, x2 = yJ[3 * k + 2] * d;
      yJ[3 * k] = x0;
      yJ[3 * k + 1] = x1;
      yJ[3 * k + 2] = x2;
      const T* u = U + int64_t{w} * k;
      for (int i = 0; i < k; ++i) {
        yJ[3 * i] -= u[i] * x0;
        yJ[3 * i + 1] -= u[i] * x1;
        yJ[3 * i + 2] -= u[i] * x2;
      }
    }
  }
}

template <class T>
void CholeskySolver::sweeps(const T* values, double* y) const {
  const size_t top_rows = static_cast<size_t>(n_ - top_col_);
  const int top = part_start_[kFactorParts], supernodes = static_cast<int>(col_start_.size()) - 1;
  // Forward (L z = b): the parts, each with its own sums for the rows above the cut, then those
  // sums in part order, then the rows above the cut.
  parallel::for_tasks(kFactorParts, n_ > 4096, [&](int t) {
    forward(values, part_start_[t], part_start_[t + 1], y, top_sums_.data() + 3 * top_rows * t);
  });
  for (int t = 0; t < kFactorParts; ++t) {
    double* sums = top_sums_.data() + 3 * top_rows * t;
    double* target = y + 3 * static_cast<size_t>(top_col_);
    for (size_t i = 0; i < 3 * top_rows; ++i) {
      target[i] -= sums[i];
      sums[i] = 0.0;
    }
  }
  forward(values, top, supernodes, y, nullptr);
  // Backward (L^T x = z): the rows above the cut first, then the parts.
  backward(values, top, supernodes, y);
  parallel::for_tasks(kFactorParts, n_ > 4096, [&](int t) { backward(values, part_start_[t], part_start_[t + 1], y); });
}

void CholeskySolver::subtract_product(const double* x, double* r) const {
  // Column j holds A(i, j) for i >= j: row j's entries right of the diagonal (gathered, in parallel)
  // and column j's below it (scattered to rows i > j, in one pass in column order: deterministic).
  parallel::for_each(n_, parallel::kMinParallelItems, [&](int j) {
    double s0 = 0, s1 = 0, s2 = 0;
    for (int k = a_start_[j]; k < a_start_[j + 1]; ++k) {
      const double a = a_values_[k];
      const double* xi = x + 3 * static_cast<size_t>(a_rows_[k]);
      s0 += a * xi[0], s1 += a * xi[1], s2 += a * xi[2];
    }
    double* rj = r + 3 * static_cast<size_t>(j);
    rj[0] -= s0, rj[1] -= s1, rj[2] -= s2;
  });
  for (int j = 0; j < n_; ++j) {
    const double* xj = x + 3 * static_cast<size_t>(j);
    for (int k = a_start_[j]; k < a_start_[j + 1]; ++k) {
      const int i = a_rows_[k];
      if (i == j) continue;
      const double a = a_values_[k];
      double* ri = r + 3 * static_cast<size_t>(i);
      ri[0] -= a * xj[0], ri[1] -= a * xj[1], ri[2] -= a * xj[2];
    }
  }
}

void CholeskySolver::solve_ordered_in_place(double* y) const {
  if (n_ == 0) return;
  if (values_) {
    sweeps(values_.get(), y);
    return;
  }
  // Single precision: x = M^-1 b, then x += M^-1 (b - A x).
  double* r = refine_.data();
  const size_t size = 3 * static_cast<size_t>(n_);
  std::copy(y, y + size, r);
  sweeps(values_single_.get(), y);
  subtract_product(y, r);
  sweeps(values_single_.get(), r);
  parallel::for_each(n_, parallel::kMinParallelItems, [&](int i) {
    for (size_t k = 3 * static_cast<size_t>(i); k < 3 * static_cast<size_t>(i) + 3; ++k) y[k] += r[k];
  });
}

}  // namespace gauss

namespace gauss {

void CholeskySolver::plan_sparse(const int* rows, int count, std::vector<int>& plan) const {
  plan.clear();
  for (int i = 0; i < count; ++i)
    for (int t = super_of_col_[rows[i]]; t >= 0 && !plan_mark_[t]; t = super_parent_[t]) {
      plan_mark_[t] = 1;
      plan.push_back(t);
    }
  std::sort(plan.begin(), plan.end());  // children before their parents
  for (int t : plan) plan_mark_[t] = 0;
}

void CholeskySolver::solve_planned_in_place(double* y, const std::vector<int>& plan) const {
  // As sweeps(): the plan's supernodes in each part on their own thread (a part's rows are its own,
  // and what it owes the rows above the cut goes into its own sums), then the sums in part order and
  // the supernodes above the cut. A supernode owes only rows of its ancestors, which are in the plan,
  // so only the plan's rows are read or written.
  size_t bound[kFactorParts + 1];
  for (int t = 0; t <= kFactorParts; ++t)
    bound[t] = static_cast<size_t>(std::lower_bound(plan.begin(), plan.end(), part_start_[t]) - plan.begin());
  const size_t top_rows = static_cast<size_t>(n_ - top_col_);
  const bool split = plan_splits(plan);
  const auto planned = [&](const auto* values) {
    parallel::for_tasks(kFactorParts, split, [&](int t) {
      double* sums = top_sums_.data() + 3 * top_rows * t;
      for (size_t i = bound[t]; i < bound[t + 1]; ++i) forward(values, plan[i], plan[i] + 1, y, sums);
    });
    for (size_t i = bound[kFactorParts]; i < plan.size(); ++i)
      for (int r = col_start_[plan[i]]; r < col_start_[plan[i] + 1]; ++r)
        for (int t = 0; t < kFactorParts; ++t) {
          double* owed = top_sums_.data() + 3 * top_rows * t + 3 * static_cast<size_t>(r - top_col_);
          double* target = y + 3 * static_cast<size_t>(r);
          for (int k = 0; k < 3; ++k) target[k] -= owed[k], owed[k] = 0.0;
        }
    for (size_t i = bound[kFactorParts]; i < plan.size(); ++i) forward(values, plan[i], plan[i] + 1, y, nullptr);
    for (size_t i = plan.size(); i-- > bound[kFactorParts];) backward(values, plan[i], plan[i] + 1, y);
    parallel::for_tasks(kFactorParts, split, [&](int t) {
      for (size_t i = bound[t + 1]; i-- > bound[t];) backward(values, plan[i], plan[i] + 1, y);
    });
  };
  if (values_) planned(values_.get());
  else planned(values_single_.get());
}

bool CholeskySolver::plan_splits(const std::vector<int>& plan) const {
  for (int t = 0; t < kFactorParts; ++t) {
    const auto first = std::lower_bound(plan.begin(), plan.end(), part_start_[t]);
    if (std::lower_bound(first, plan.end(), part_start_[t + 1]) - first < static_cast<std::ptrdiff_t>(kMinSplitPlan))
      return false;
  }
  return true;
}

long long CholeskySolver::plan_nonzeros(const std::vector<int>& plan) const {
  long long nonzeros = 0;
  for (int t : plan) {
    nonzeros += supernode_nonzeros(col_start_[t + 1] - col_start_[t], row_start_[t + 1] - row_start_[t]);
  }
  return nonzeros;
}

}  // namespace gauss
