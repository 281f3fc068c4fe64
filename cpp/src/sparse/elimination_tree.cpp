#include "gauss/sparse/elimination_tree.h"

#include <algorithm>

namespace gauss {

LowerColumns permute_lower(const Eigen::SparseMatrix<double>& A_lower, const std::vector<int>& new_of_old,
                           bool with_values) {
  LowerColumns P;
  const int n = P.n = static_cast<int>(A_lower.rows());
  P.start.assign(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A_lower, j); it; ++it)
      if (it.row() >= j) ++P.start[std::min(new_of_old[it.row()], new_of_old[j]) + 1];
  for (int j = 0; j < n; ++j) P.start[j + 1] += P.start[j];
  P.rows.resize(P.start[n]);
  if (with_values) P.values.resize(P.start[n]);
  std::vector<int> fill(P.start.begin(), P.start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A_lower, j); it; ++it)
      if (it.row() >= j) {
        const int a = new_of_old[it.row()], b = new_of_old[j];
        const int slot = fill[std::min(a, b)]++;
        P.rows[slot] = std::max(a, b);
        if (with_values) P.values[slot] = it.value();
      }
  return P;
}

std::vector<int> elimination_tree(const LowerColumns& A) {
  const int n = A.n;
  // Row k's entries left of the diagonal (the pattern by rows), which Liu's algorithm walks in row order.
  std::vector<int> row_start(n + 1, 0), row_cols(A.rows.size());
  for (int j = 0; j < n; ++j)
    for (int p = A.start[j]; p < A.start[j + 1]; ++p)
      if (A.rows[p] > j) ++row_start[A.rows[p] + 1];
  for (int k = 0; k < n; ++k) row_start[k + 1] += row_start[k];
  {
    std::vector<int> fill(row_start.begin(), row_start.end() - 1);
    for (int j = 0; j < n; ++j)
      for (int p = A.start[j]; p < A.start[j + 1]; ++p)
        if (A.rows[p] > j) row_cols[fill[A.rows[p]]++] = j;
  }
  // Row k joins, through each of its entries (k, j), the tree that holds j: k becomes the parent of
  // that tree's root. `ancestor` shortcuts to the current root (path compression).
  std::vector<int> parent(n, -1), ancestor(n, -1);
  for (int k = 0; k < n; ++k)
    for (int p = row_start[k]; p < row_start[k + 1]; ++p)
      for (int i = row_cols[p]; i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
  return parent;
}

std::vector<int> postorder(const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> first_child(n, -1), next_sibling(n, -1);
  for (int j = n - 1; j >= 0; --j)  // descending, so that each child list comes out ascending
    if (parent[j] >= 0) {
      next_sibling[j] = first_child[parent[j]];
      first_child[parent[j]] = j;
    }
  std::vector<int> post, stack;
  post.reserve(n);
  for (int root = 0; root < n; ++root) {
    if (parent[root] >= 0) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int j = stack.back();
      if (first_child[j] >= 0) {  // descend; the child is unlinked so j is emitted on its next visit
        const int c = first_child[j];
        first_child[j] = next_sibling[c];
        stack.push_back(c);
      } else {
        post.push_back(j);
        stack.pop_back();
      }
    }
  }
  return post;
}

std::vector<int> column_counts(const LowerColumns& A, const std::vector<int>& parent) {
  // Row i of L is nonzero in the "row subtree" T_i: the tree paths from each column j < i with
  // A(i, j) != 0 up to i. count[j] = #{i : j in T_i}. Each T_i is charged to the tree as +1 at each of
  // its leaves, -1 at the lowest common ancestor of each two consecutive leaves and -1 at i's parent;
  // the sum of the charges over the subtree of j is then 1 exactly when j lies in T_i, so summing
  // all charges over subtrees gives the counts.
  const int n = A.n;
  std::vector<int> first(n, -1);  // first[j]: smallest column in j's subtree (columns are postordered)
  for (int k = 0; k < n; ++k)
    for (int j = k; j != -1 && first[j] == -1; j = parent[j]) first[j] = k;
  std::vector<int> charge(n, 0), last_seen(n, -1), previous_leaf(n, -1), ancestor(n);
  for (int j = 0; j < n; ++j) ancestor[j] = j;
  auto find = [&](int x) {
    int root = x;
    while (ancestor[root] != root) root = ancestor[root];
    while (ancestor[x] != root) {
      const int next = ancestor[x];
      ancestor[x] = root;
      x = next;
    }
    return root;
  };
  for (int j = 0; j < n; ++j) {
    if (first[j] == j) ++charge[j];  // a leaf of the tree: T_j = {j}
    if (parent[j] >= 0) --charge[parent[j]];
    for (int p = A.start[j]; p < A.start[j + 1]; ++p) {
      const int i = A.rows[p];
      if (i <= j) continue;
      // j is a leaf of T_i unless a column of its subtree ([first[j], j)) already had an entry in row i.
      const bool leaf = last_seen[i] < first[j];
      last_seen[i] = j;
      if (!leaf) continue;
      ++charge[j];
      // Columns before j are finished and linked to their parents, so the root of the previous
      // leaf's set is the lowest ancestor it shares with j.
      if (previous_leaf[i] >= 0) --charge[find(previous_leaf[i])];
      previous_leaf[i] = j;
    }
    if (parent[j] >= 0) ancestor[j] = parent[j];
  }
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) charge[parent[j]] += charge[j];
  return charge;
}

}  // namespace gauss
