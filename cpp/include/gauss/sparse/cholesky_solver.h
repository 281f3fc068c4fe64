#pragma once
// Sparse Cholesky factorization A = L L^T of the (constant) global-step matrix, with a solve that
// carries all three coordinate columns through one forward and one backward sweep, so L is streamed
// from memory twice per step instead of six times (that is what bounds the global step on big meshes).
//
// factor() = nested-dissection ordering (nested_dissection.h) + supernodal symbolic analysis
// (supernodal_analysis.h) + a check that the factor fits in the memory the machine has
// (memory_budget.h) + the numeric supernodal factorization (supernodal_factor.h). L stays in its
// supernodal blocks: below a supernode's dense diagonal block every row of L is a contiguous run of
// values, so the sweeps read L with no index per entry.
//
// Threads: the elimination tree is always cut into two groups of subtrees (kFactorParts) plus the
// rows above the cut, whatever the number of threads (the cut decides the numbering and with it the
// rounding). The two groups are factored and swept in parallel, the rows above the cut after them
// (their big dense blocks tile by tile, the tiling fixed by the block sizes), so results are
// bit-identical for any thread count. Eigen blocks its dense products by the cache sizes it detects,
// so a machine with other caches may round differently.
//
// Single precision: from kSinglePrecisionUnknowns unknowns up, L's values are kept in floats, half
// the memory (at 2M vertices 0.6 GB of 1.2 GB: what lets a sculpt's finish fit in 4 GB). The
// factorization itself runs in doubles; its values are then rounded within the same block, which
// gives its second half back, so the floats never sit beside the doubles. Each solve then
// refines its result once against A (kept, its lower triangle: 12 bytes a nonzero of A, a tenth of
// the factor's): x = M^-1 b, x += M^-1 (b - A x), M the rounded factor's product. Rounding changes
// L by a relative 6e-8; the first solve is off by about that times L's condition number (the square
// root of A's), and the refinement squares that error (on a 60K-vertex Laplacian: 9e-8 of the
// solution unrefined, under 1e-9 refined), for a second sweep of the factor and a product with A.
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <vector>

#include "gauss/util/progress.h"
#include "gauss/sparse/supernodal_factor.h"

namespace gauss {

inline constexpr int kSinglePrecisionUnknowns = 1'000'000;

class CholeskySolver {
 public:
  // automatic: single from kSinglePrecisionUnknowns unknowns up, else double.
  enum class Precision { automatic, double_values, single_values };
  // A: symmetric positive definite n by n (only the lower triangle is read). Taken by value and freed
  // once the symbolic analysis holds its own copy, before the numeric factorization allocates the
  // factor: a caller that has no further use for A moves it in, and the set-up's peak has one copy.
  // progress: receives SetupPhase::ordering .. factorizing (started and finished here unless the
  //   caller already started it); cancel() makes factor() throw Cancelled.
  // Throws std::runtime_error if A is not numerically positive definite, OutOfMemory (memory_budget.h)
  // if the factor would not fit in the available memory, Cancelled. On any exception the solver keeps
  // its previous factor, unchanged.
  void factor(Eigen::SparseMatrix<double> A, Progress* progress = nullptr,
              Precision precision = Precision::automatic);
  bool single_precision() const { return values_single_ != nullptr; }
  // Solves A X = B in place; B: n by 3, row-major (x, y, z of one unknown adjacent), in elimination
  // order: row position(i) holds unknown i (callers assemble B in that order, which saves two
  // permuting passes). No allocation happens here; one solve at a time per solver.
  void solve_ordered_in_place(double* Y) const;
  int position(int i) const { return new_of_old_[i]; }
  // For a right-hand side that is zero but in a few rows, of which only those rows of the solution
  // are wanted (contact_springs.h): the supernodes on the elimination tree's paths from those rows
  // (in elimination order) to its root, ascending. solve_planned_in_place(Y, plan) is then
  // solve_ordered_in_place() restricted to them: Y must be zero in the plan's other rows, and the
  // solution is right in the plan's rows (the others are neither read nor written; in single
  // precision it is not refined, so right to about 1e-7 of the solution). It costs
  // plan_nonzeros(plan) of factor_nonzeros(), on two threads where plan_splits(plan) (at least
  // kMinSplitPlan of its supernodes in each of the cut's parts), else on one. One solve at a time per
  // solver, as above. plan_sparse() allocates nothing once `plan` has grown.
  void plan_sparse(const int* rows, int count, std::vector<int>& plan) const;
  void solve_planned_in_place(double* Y, const std::vector<int>& plan) const;
  long long plan_nonzeros(const std::vector<int>& plan) const;
  bool plan_splits(const std::vector<int>& plan) const;
  int size() const { return n_; }
  // Values of L stored: its lower triangle, diagonal included, plus the few explicit zeros that
  // relaxed supernodes add.
  long long factor_nonzeros() const { return nonzeros_; }

 private:
  template <class T>
  void forward(const T* values, int first_super, int last_super, double* y, double* top_sums) const;
  template <class T>
  void backward(const T* values, int first_super, int last_super, double* y) const;
  template <class T>
  void sweeps(const T* values, double* y) const;  // y := (L L^T)^-1 y, L's values in `values`
  void subtract_product(const double* x, double* r) const;  // r -= A x (A from a_start_, a_rows_, a_values_)

  int n_ = 0;
  long long nonzeros_ = 0;
  std::vector<int> new_of_old_;  // unknown -> row in elimination order
  // Supernode s: columns [col_start_[s], col_start_[s+1]), rows rows_[row_start_[s] ..], block (L's
  // rows by columns, transposed: w by m, column-major) at values_[value_start_[s]]. See
  // supernodal_analysis.h.
  std::vector<int> col_start_, row_start_, rows_;
  std::vector<int64_t> value_start_;
  FactorValues values_;                                // in double precision, else null
  std::unique_ptr<float[], FreeDeleter> values_single_;  // in single precision, else null
  // Single precision: A in elimination order, lower triangle by columns (rows unsorted within a
  // column), and the refinement's copy of the right-hand side (n by 3).
  std::vector<int> a_start_, a_rows_;
  std::vector<double> a_values_;
  mutable std::vector<double> refine_;
  std::vector<double> inv_diag_;  // 1 / L(j, j)
  // Supernodes of part t: [part_start_[t], part_start_[t+1]); the top: [part_start_.back(), #S).
  std::vector<int> part_start_;
  int top_col_ = 0;  // first row above the cut
  // Per part, the sums its forward sweep owes the rows above the cut (3 per row), added to those rows
  // in part order once both parts are done. Zero between solves.
  mutable std::vector<double> top_sums_;
  std::vector<int> super_of_col_;   // #rows: the supernode that holds it
  std::vector<int> super_parent_;   // #supernodes: its parent in the elimination tree, -1 for a root
  mutable std::vector<uint8_t> plan_mark_;  // #supernodes, zero between plan_sparse() calls
  // A planned solve is split between threads only with this many of its supernodes in each part: a
  // shorter plan (a few springs' paths to the root) costs less than waking a thread.
  static constexpr size_t kMinSplitPlan = 32;
};

}  // namespace gauss
