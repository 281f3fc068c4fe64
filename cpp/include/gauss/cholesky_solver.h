#pragma once
// Sparse LDL^T factorization (AMD ordering, up-looking) of the (constant) global-step matrix, with a solve that carries all
// three coordinate columns through one forward and one backward sweep: the factor is streamed from
// memory twice per step instead of six times, which is what bounds the global step on large meshes.
//
// The factorization and the sweeps also run on several threads: rows in disjoint subtrees of the elimination tree never
// read each other, so the tree is cut into one group of subtrees per thread (balanced by nonzeros)
// plus the rows above the cut, which run alone. Every row is still computed by the same sequence of
// operations, so the result does not depend on the number of threads.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace gauss {

class CholeskySolver {
 public:
  // A: symmetric positive definite n by n (only the lower triangle is read).
  // Throws std::runtime_error if A is not numerically positive definite.
  void factor(const Eigen::SparseMatrix<double>& A);
  // Solves A X = B in place; B: n by 3, row-major (x, y, z of one unknown adjacent), in elimination
  // order: row position(i) holds unknown i (callers assemble B in that order, which saves two
  // permuting passes). No allocation happens here.
  void solve_ordered_in_place(double* Y) const;
  int position(int i) const { return new_of_old_[i]; }
  int size() const { return n_; }
  long long factor_nonzeros() const { return static_cast<long long>(col_values_.size()); }

 private:
  int n_ = 0;
  std::vector<int> new_of_old_;  // unknown -> row in elimination order
  // The strictly lower part of L twice: by rows for the forward sweep and by columns (= rows of L^T)
  // for the backward sweep, so both sweeps gather into registers instead of scattering to memory.
  std::vector<int> row_start_, row_cols_;
  std::vector<double> row_values_;
  std::vector<int> col_start_, col_rows_;
  std::vector<double> col_values_;
  std::vector<double> inv_diag_;  // 1 / D
  // Rows are numbered group by group: thread t's subtrees are rows [part_start_[t], part_start_[t+1]),
  // the rows above the cut are [part_start_.back(), n).
  std::vector<int> part_start_;
  // Groups of rows (ascending): one per part, then the rows above the cut.
  std::vector<std::vector<int>> partition_elimination_tree(const std::vector<int>& parent,
                                                           const std::vector<double>& work, int parts) const;
};

}  // namespace gauss
