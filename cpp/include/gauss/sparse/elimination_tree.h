#pragma once
// What the sparsity pattern of a symmetric matrix says about its Cholesky factor L, without computing
// L: the elimination tree (Liu 1990) and the number of entries in each column of L (Gilbert, Ng &
// Peyton 1994), both in time nearly linear in the entries of A.
#include <Eigen/SparseCore>
#include <vector>

namespace gauss {

// The lower triangle of a symmetric n by n matrix, by columns: column j holds rows >= j, in
// rows[start[j] .. start[j+1]) with values[...] (values may be empty when only the pattern matters).
struct LowerColumns {
  int n = 0;
  std::vector<int> start, rows;
  std::vector<double> values;
};

// The lower triangle of P A P^T (entries of A above the diagonal are ignored), where row i of A
// becomes row new_of_old[i]. A_lower: n by n; new_of_old: a permutation of 0..n-1. Rows come out
// unsorted within a column.
LowerColumns permute_lower(const Eigen::SparseMatrix<double>& A_lower, const std::vector<int>& new_of_old,
                           bool with_values);

// Elimination tree: parent[j] (n) is the parent of column j (always > j), or -1 for a root.
std::vector<int> elimination_tree(const LowerColumns& A);

// A postorder of the elimination forest: post[k] (n) is the column visited k-th; children are visited
// in ascending order and every subtree occupies consecutive positions.
std::vector<int> postorder(const std::vector<int>& parent);

// count[j] (n): entries of column j of L, the diagonal included. A's columns must already be numbered
// in a postorder of its elimination tree `parent`.
std::vector<int> column_counts(const LowerColumns& A, const std::vector<int>& parent);

}  // namespace gauss
