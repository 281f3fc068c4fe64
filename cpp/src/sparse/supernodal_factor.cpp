#include "gauss/sparse/supernodal_factor.h"

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <exception>
#include <new>
#include <stdexcept>
#include <vector>

#include "gauss/sparse/dense_block.h"
#include "gauss/util/memory_budget.h"
#include "gauss/util/parallel.h"

namespace gauss {
namespace {

using MatrixMap = Eigen::Map<Eigen::MatrixXd>;
using ConstMatrixMap = Eigen::Map<const Eigen::MatrixXd>;

// Updates with fewer multiply-adds than this are computed by plain loops: Eigen's product set-up
// costs more than the arithmetic.
constexpr int64_t kSmallUpdate = 2048;
// A big supernode can receive thousands of updates: the cancel flag is polled every this many.
constexpr int kUpdatesPerCheck = 32;

struct Workspace {
  std::vector<int> position;   // n: row of L -> column of the block being computed
  std::vector<double> update;  // one slice of the largest update (max_update_columns * kUpdateSlice)
};

FactorValues allocate(int64_t count, const char* what) {
  FactorValues p(static_cast<double*>(std::malloc(sizeof(double) * std::max<int64_t>(count, 1))));
  if (!p) throw OutOfMemory(std::string("not enough memory for ") + what + " (" + format_bytes(8 * count) + ")");
  return p;
}

class Factorization {
 public:
  Factorization(const SupernodalStructure& S, double* values) : S_(S), values_(values) {}

  double* block(int s) const { return values_ + S_.value_start[s]; }
  int width(int s) const { return S_.col_start[s + 1] - S_.col_start[s]; }
  int height(int s) const { return S_.row_start[s + 1] - S_.row_start[s]; }
  const int* rows(int s) const { return S_.rows.data() + S_.row_start[s]; }

  // Block s := A's entries (target: block s or a block of the same layout).
  void assemble(int s, double* U, Workspace& ws) const {
    const int f = S_.col_start[s], w = width(s), m = height(s);
    std::fill(U, U + int64_t{w} * m, 0.0);
    set_positions(s, ws);
    for (int k = 0; k < w; ++k)
      for (int p = S_.A.start[f + k]; p < S_.A.start[f + k + 1]; ++p)
        U[k + int64_t{w} * ws.position[S_.A.rows[p]]] += S_.A.values[p];
  }

  void set_positions(int s, Workspace& ws) const {
    const int* R = rows(s);
    for (int c = 0, m = height(s); c < m; ++c) ws.position[R[c]] = c;
  }

  // Left-looking: subtracts from block s the updates of the descendants listed for it. ws.position
  // must be set for s. Stops early (the caller sees it) once the progress is cancelled.
  void pull_updates(int s, Workspace& ws, const Progress& progress) const {
    for (int t = S_.update_start[s]; t < S_.update_start[s + 1]; ++t) {
      if (t % kUpdatesPerCheck == 0 && progress.cancelled()) return;
      const int d = S_.update_source[t], offset = S_.update_offset[t];
      const int* Rd = rows(d) + offset;
      const int f = S_.col_start[s], w = width(s);
      subtract_update(
          d, offset, S_.update_count[t], [&](int b) { return block(s) + int64_t{w} * ws.position[Rd[b]]; },
          [&](int a) { return Rd[a] - f; }, ws);
    }
  }

  // Right-looking: subtracts the updates of part supernode d from the top blocks, written at
  // `top` (a copy of the top's blocks: value_start[s] - top_begin is block s's offset in it).
  void push_updates(int d, double* top, int64_t top_begin, Workspace& ws) const {
    const int m = height(d);
    const int* R = rows(d);
    for (int p = S_.top_offset[d]; p < m;) {
      const int s = S_.super_of_col[R[p]], f = S_.col_start[s], w = width(s);
      int q = p;
      while (q < m && R[q] < S_.col_start[s + 1]) ++q;
      const int* Rs = rows(s);
      const int ms = height(s);
      double* U = top + (S_.value_start[s] - top_begin);
      // Rows of d are a subset of s's rows: find each by bisection (s's rows are sorted).
      subtract_update(d, p, q - p,
                      [&](int b) {
                        const int c = static_cast<int>(std::lower_bound(Rs, Rs + ms, R[p + b]) - Rs);
                        return U + int64_t{w} * c;
                      },
                      [&](int a) { return R[p + a] - f; }, ws);
      p = q;
    }
  }

 private:
  // Target -= the update of descendant d from its rows R_d[offset ..], of which the first `cols` are
  // columns of the target: column(b) points at the target column of row R_d[offset + b], row(a) is
  // the target row of R_d[offset + a]. Only the upper triangle of the target's diagonal block
  // (a <= b) is needed.
  template <class Column, class Row>
  void subtract_update(int d, int offset, int cols, Column&& column, Row&& row, Workspace& ws) const {
    const int wd = width(d), rows_below = height(d) - offset;
    const double* Ud = block(d) + int64_t{wd} * offset;  // column b: row R_d[offset + b] of L_d
    if (int64_t{wd} * cols * rows_below < kSmallUpdate) {
      for (int b = 0; b < rows_below; ++b) {
        double* target = column(b);
        const double* ub = Ud + int64_t{wd} * b;
        for (int a = 0; a < cols && a <= b; ++a) {
          const double* ua = Ud + int64_t{wd} * a;
          double sum = 0;
          for (int k = 0; k < wd; ++k) sum += ua[k] * ub[k];
          target[row(a)] -= sum;
        }
      }
      return;
    }
    for (int b0 = 0; b0 < rows_below; b0 += kUpdateSlice) {
      const int b1 = std::min(b0 + kUpdateSlice, rows_below);
      MatrixMap W(ws.update.data(), cols, b1 - b0);
      W.noalias() = ConstMatrixMap(Ud, wd, cols).transpose() * ConstMatrixMap(Ud + int64_t{wd} * b0, wd, b1 - b0);
      for (int b = b0; b < b1; ++b) {
        double* target = column(b);
        const double* wb = ws.update.data() + int64_t{cols} * (b - b0);
        for (int a = 0; a < cols && a <= b; ++a) target[row(a)] -= wb[a];
      }
    }
  }

  const SupernodalStructure& S_;
  double* values_;
};

}  // namespace

FactorValues factor_supernodal(const SupernodalStructure& S, Progress& progress) {
  FactorValues values = allocate(S.num_values(), "the factor");
  const Factorization F(S, values.get());
  const int first_top = S.part_start[kFactorParts], num_super = S.num_supernodes();
  const int64_t top_begin = S.value_start[first_top], top_count = S.top_values();
  // Part 0 sends its updates straight into the top's blocks, every other part into a zeroed copy
  // of them that the top adds in part order: the sums never depend on which thread finished first.
  std::vector<FactorValues> sent(kFactorParts);
  for (int t = 1; t < kFactorParts; ++t) {
    sent[t] = allocate(top_count, "the factorization's top blocks");
    std::fill(sent[t].get(), sent[t].get() + top_count, 0.0);
  }
  std::vector<Workspace> workspaces(kFactorParts);
  for (Workspace& ws : workspaces) {
    ws.position.resize(S.n);
    ws.update.resize(int64_t{S.max_update_columns} * kUpdateSlice);
  }
  for (int s = first_top; s < num_super; ++s) F.assemble(s, F.block(s), workspaces[0]);

  double total_work = 0;
  for (double w : S.work) total_work += w;
  total_work = std::max(total_work, 1.0);
  std::atomic<int64_t> done{0};  // work units of finished supernodes
  auto report = [&](int s) {
    const int64_t d = done.fetch_add(static_cast<int64_t>(S.work[s]), std::memory_order_relaxed);
    progress.advance(double(d + static_cast<int64_t>(S.work[s])) / total_work);
  };
  std::atomic<bool> failed{false};
  std::vector<std::exception_ptr> errors(kFactorParts + 1);
  parallel::for_tasks(kFactorParts, S.n > 4096, [&](int t) {
    try {
      Workspace& ws = workspaces[t];
      double* top = t == 0 ? values.get() + top_begin : sent[t].get();
      for (int s = S.part_start[t]; s < S.part_start[t + 1]; ++s) {
        if (failed.load(std::memory_order_relaxed) || progress.cancelled()) return;
        F.assemble(s, F.block(s), ws);
        F.pull_updates(s, ws, progress);
        if (progress.cancelled()) return;
        if (!factor_block(F.block(s), F.width(s), F.height(s), false, progress)) {
          failed.store(!progress.cancelled(), std::memory_order_relaxed);
          return;
        }
        F.push_updates(s, top, top_begin, ws);
        report(s);
      }
    } catch (...) {
      errors[t] = std::current_exception();
    }
  });
  const bool parts_ok = std::none_of(errors.begin(), errors.end(), [](auto& e) { return bool(e); });
  if (parts_ok && !failed && !progress.cancelled()) {
    try {
      // The top: add what the other parts sent, pull the top's own updates, factor (tiles in parallel).
      double* top = values.get() + top_begin;
      for (int t = 1; t < kFactorParts; ++t) {
        const double* from = sent[t].get();
        for (int64_t i = 0; i < top_count; ++i) top[i] += from[i];
        sent[t].reset();
      }
      for (int s = first_top; s < num_super && !progress.cancelled(); ++s) {
        F.set_positions(s, workspaces[0]);
        F.pull_updates(s, workspaces[0], progress);
        if (progress.cancelled()) break;
        if (!factor_block(F.block(s), F.width(s), F.height(s), S.n > 4096, progress)) {
          failed = !progress.cancelled();
          break;
        }
        report(s);
      }
    } catch (...) {
      errors[kFactorParts] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) {
      try {
        std::rethrow_exception(e);
      } catch (const std::bad_alloc&) {
        throw OutOfMemory("not enough memory for the factorization's dense blocks");
      }
    }
  progress.check();
  if (failed)
    throw std::runtime_error("the mesh's Laplacian is not positive definite (the mesh is too degenerate to solve)");
  return values;
}

}  // namespace gauss
