#include "gauss/sparse/supernodal_analysis.h"

#include <algorithm>
#include <climits>
#include <queue>
#include <utility>

#include "gauss/util/memory_budget.h"

namespace gauss {
namespace {

// Relaxed amalgamation: a supernode merges into its parent when the merged block has at most this
// share of explicit zeros for its width. Wider blocks make the dense kernels faster, but every step's
// sweeps read every zero: these limits, tighter than CHOLMOD's defaults (which merge any block of up
// to 4 columns and allow 80% zeros up to 16), store fewer values and solve faster at the same
// factorization time (measured: docs/performance.md#set-up-at-scale).
bool worth_merging(int64_t width, double zero_share) {
  if (width <= 4) return zero_share < 0.3;
  if (width <= 16) return zero_share < 0.2;
  if (width <= 48) return zero_share < 0.05;
  return zero_share < 0.02;
}

// First column of each supernode (#S + 1 entries), for a postordered tree with column counts.
std::vector<int> relaxed_supernodes(const std::vector<int>& parent, const std::vector<int>& count) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> children(n, 0);
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) ++children[parent[j]];
  // Fundamental supernodes: column j continues j-1's supernode if it is j-1's only parent and child
  // and its rows are j-1's minus j-1 itself.
  std::vector<int> first{0};
  for (int j = 1; j < n; ++j)
    if (!(parent[j - 1] == j && children[j] == 1 && count[j - 1] == count[j] + 1)) first.push_back(j);
  first.push_back(n);
  const int F = static_cast<int>(first.size()) - 1;
  // Merge top-down, so a supernode's parent group is complete when it is considered. A group's rows
  // are its first column's: the child's columns plus the parent group's rows.
  std::vector<int64_t> width(F), height(F), nonzeros(F, 0);
  for (int f = 0; f < F; ++f) {
    width[f] = first[f + 1] - first[f];
    height[f] = count[first[f]];
    for (int j = first[f]; j < first[f + 1]; ++j) nonzeros[f] += count[j];
  }
  std::vector<uint8_t> joined(F, 0);
  for (int f = F - 2; f >= 0; --f) {
    if (parent[first[f + 1] - 1] != first[f + 1]) continue;  // the next supernode is not the parent
    const int g = f + 1;
    const int64_t w = width[f] + width[g], h = width[f] + height[g];
    const int64_t stored = w * h - w * (w - 1) / 2;
    if (!worth_merging(w, double(stored - nonzeros[f] - nonzeros[g]) / double(stored))) continue;
    joined[g] = 1;
    width[f] = w;
    height[f] = h;
    nonzeros[f] += nonzeros[g];
  }
  std::vector<int> starts;
  for (int f = 0; f < F; ++f)
    if (!joined[f]) starts.push_back(first[f]);
  starts.push_back(n);
  return starts;
}

// Cuts a tree (parent[s] > s) into `parts` groups of whole subtrees of about equal work plus the nodes
// above the cut: group[s] in 0..parts-1, or `parts` for the top. Cuts off the heaviest subtree's root
// step by step, estimating the time of each cut as the top's work plus the larger of the heaviest
// remaining subtree and an even share, keeps the best number of steps, then packs the remaining
// subtrees into the parts (largest first, into the lightest part).
std::vector<int> cut_tree(const std::vector<int>& parent, const std::vector<double>& work, int parts) {
  const int S = static_cast<int>(parent.size());
  std::vector<int> child_start(S + 1, 0), children(S);
  std::vector<double> subtree(work);
  for (int s = 0; s < S; ++s)
    if (parent[s] >= 0) {
      subtree[parent[s]] += subtree[s];
      ++child_start[parent[s] + 1];
    }
  for (int s = 0; s < S; ++s) child_start[s + 1] += child_start[s];
  {
    std::vector<int> fill(child_start.begin(), child_start.end() - 1);
    for (int s = 0; s < S; ++s)
      if (parent[s] >= 0) children[fill[parent[s]]++] = s;
  }
  double total = 0;
  for (int s = 0; s < S; ++s)
    if (parent[s] < 0) total += subtree[s];
  std::vector<int> group(S, parts);
  auto lighter = [&](int a, int b) { return subtree[a] != subtree[b] ? subtree[a] < subtree[b] : a > b; };
  auto run = [&](int steps, bool apply) {
    std::priority_queue<int, std::vector<int>, decltype(lighter)> heap(lighter);
    for (int s = 0; s < S; ++s)
      if (parent[s] < 0) heap.push(s);
    double top = 0, best = 2 * total;
    int best_steps = 0;
    for (int step = 0; !heap.empty(); ++step) {
      const double estimate = top + std::max(subtree[heap.top()], (total - top) / parts);
      if (estimate < best) best = estimate, best_steps = step;
      if (step == steps || parts == 1 || top > 0.5 * total || estimate <= 1.02 * total / parts) break;
      const int r = heap.top();
      heap.pop();
      top += work[r];
      for (int k = child_start[r]; k < child_start[r + 1]; ++k) heap.push(children[k]);
    }
    if (apply) {
      std::vector<double> load(parts, 0.0);
      std::vector<int> stack;
      for (; !heap.empty(); heap.pop()) {  // heaviest first
        const int bin = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
        load[bin] += subtree[heap.top()];
        stack.assign(1, heap.top());
        while (!stack.empty()) {
          const int v = stack.back();
          stack.pop_back();
          group[v] = bin;
          for (int k = child_start[v]; k < child_start[v + 1]; ++k) stack.push_back(children[k]);
        }
      }
    }
    return best_steps;
  };
  run(run(-1, false), true);
  return group;
}

void fail_if_too_big(int64_t count, const char* what) {
  if (count > INT_MAX)
    throw OutOfMemory(std::string("the factorization is too big to represent (") + what + " exceed 2^31)");
}

}  // namespace

int64_t SupernodalStructure::top_values() const {
  return num_values() - value_start[part_start[kFactorParts]];
}

int64_t SupernodalStructure::numeric_bytes() const {
  const int64_t doubles = num_values() + int64_t{kFactorParts - 1} * top_values() +
                          int64_t{kFactorParts} * max_update_columns * kUpdateSlice + n +
                          int64_t{3} * kFactorParts * (n - top_col);
  return 8 * doubles + int64_t{4} * kFactorParts * n;
}

SupernodalStructure analyse_supernodal(const Eigen::SparseMatrix<double>& A_lower,
                                       const std::vector<int>& old_of_new, Progress& progress) {
  const int n = static_cast<int>(A_lower.rows());
  SupernodalStructure S;
  S.n = n;
  // 1. The elimination tree in the given order, renumbered in postorder (same fill; subtrees and
  // chains become consecutive columns), and the column counts of L.
  std::vector<int> post_of_old(n), parent(n, -1), count;
  {
    std::vector<int> given(n);
    for (int k = 0; k < n; ++k) given[old_of_new[k]] = k;
    std::vector<int> given_parent = elimination_tree(permute_lower(A_lower, given, false));
    progress.advance(0.15);
    const std::vector<int> post = postorder(given_parent);
    std::vector<int> post_of_given(n);
    for (int k = 0; k < n; ++k) post_of_given[post[k]] = k;
    for (int k = 0; k < n; ++k)
      if (given_parent[post[k]] >= 0) parent[k] = post_of_given[given_parent[post[k]]];
    for (int i = 0; i < n; ++i) post_of_old[i] = post_of_given[given[i]];
    progress.check();
    count = column_counts(permute_lower(A_lower, post_of_old, false), parent);
  }
  progress.advance(0.35);
  progress.check();

  // 2. Supernodes, their tree, and the cut into parts (work: the dense column updates, sum of h^2).
  const std::vector<int> first = relaxed_supernodes(parent, count);
  const int num_super = static_cast<int>(first.size()) - 1;
  std::vector<int> super_of_post(n), super_parent(num_super, -1);
  std::vector<double> column_work(num_super, 0.0);
  for (int s = 0; s < num_super; ++s)
    for (int j = first[s]; j < first[s + 1]; ++j) super_of_post[j] = s;
  for (int s = 0; s < num_super; ++s) {
    const int p = parent[first[s + 1] - 1];
    if (p >= 0) super_parent[s] = super_of_post[p];
    const double h = count[first[s]];
    for (int k = 0; k < first[s + 1] - first[s]; ++k) column_work[s] += (h - k) * (h - k);
  }
  const std::vector<int> group = cut_tree(super_parent, column_work, kFactorParts);

  // 3. Final numbering: supernodes part by part, then the top, each group in ascending order (still
  // children before parents); columns follow their supernodes.
  std::vector<int> super_order;
  S.part_start.assign(1, 0);
  for (int g = 0; g <= kFactorParts; ++g) {
    for (int s = 0; s < num_super; ++s)
      if (group[s] == g) super_order.push_back(s);
    S.part_start.push_back(static_cast<int>(super_order.size()));
  }
  S.part_start.pop_back();  // the top is [part_start[kFactorParts], #S)
  std::vector<int> new_of_post(n), new_super(num_super);
  S.col_start.assign(1, 0);
  for (int k = 0; k < num_super; ++k) {
    const int s = super_order[k];
    new_super[s] = k;
    for (int j = first[s]; j < first[s + 1]; ++j) new_of_post[j] = S.col_start.back() + (j - first[s]);
    S.col_start.push_back(S.col_start.back() + first[s + 1] - first[s]);
  }
  S.top_col = S.col_start[S.part_start[kFactorParts]];
  S.new_of_old.resize(n);
  for (int i = 0; i < n; ++i) S.new_of_old[i] = new_of_post[post_of_old[i]];
  S.super_of_col.resize(n);
  for (int s = 0; s < num_super; ++s)
    for (int j = S.col_start[s]; j < S.col_start[s + 1]; ++j) S.super_of_col[j] = s;
  std::vector<int> child_start(num_super + 1, 0), children(num_super);
  for (int s = 0; s < num_super; ++s)
    if (super_parent[s] >= 0) ++child_start[new_super[super_parent[s]] + 1];
  for (int s = 0; s < num_super; ++s) child_start[s + 1] += child_start[s];
  {
    std::vector<int> fill(child_start.begin(), child_start.end() - 1);
    for (int k = 0; k < num_super; ++k) {
      const int s = super_order[k];
      if (super_parent[s] >= 0) children[fill[new_super[super_parent[s]]]++] = k;
    }
  }
  S.A = permute_lower(A_lower, S.new_of_old, true);
  progress.advance(0.55);
  progress.check();

  // 4. Rows of each supernode: its columns, then (ascending) A's rows below them and its children's.
  std::vector<int> mark(n, -1);
  S.row_start.assign(1, 0);
  for (int s = 0; s < num_super; ++s) {
    const int f = S.col_start[s], l = S.col_start[s + 1];
    for (int j = f; j < l; ++j) S.rows.push_back(j);
    const size_t below = S.rows.size();
    auto add = [&](int r) {
      if (r >= l && mark[r] != s) {
        mark[r] = s;
        S.rows.push_back(r);
      }
    };
    for (int j = f; j < l; ++j)
      for (int p = S.A.start[j]; p < S.A.start[j + 1]; ++p) add(S.A.rows[p]);
    for (int k = child_start[s]; k < child_start[s + 1]; ++k) {
      const int c = children[k];
      for (int p = S.row_start[c] + (S.col_start[c + 1] - S.col_start[c]); p < S.row_start[c + 1]; ++p)
        add(S.rows[p]);
    }
    std::sort(S.rows.begin() + below, S.rows.end());
    fail_if_too_big(static_cast<int64_t>(S.rows.size()), "the factor's row indices");
    S.row_start.push_back(static_cast<int>(S.rows.size()));
  }
  progress.advance(0.8);
  progress.check();

  // 5. Blocks, updates (target s, source d ascending: a counting sort by target keeps d's order), work.
  S.value_start.assign(1, 0);
  for (int s = 0; s < num_super; ++s) {
    const int64_t w = S.col_start[s + 1] - S.col_start[s], m = S.row_start[s + 1] - S.row_start[s];
    S.value_start.push_back(S.value_start.back() + w * m);
  }
  S.update_start.assign(num_super + 1, 0);
  auto for_each_update = [&](auto&& fn) {
    for (int d = 0; d < num_super; ++d) {
      const int m = S.row_start[d + 1] - S.row_start[d];
      const int* R = S.rows.data() + S.row_start[d];
      for (int p = S.col_start[d + 1] - S.col_start[d]; p < m;) {
        const int s = S.super_of_col[R[p]], end = S.col_start[s + 1];
        int q = p;
        while (q < m && R[q] < end) ++q;
        fn(s, d, p, q - p, m - p);
        p = q;
      }
    }
  };
  // Updates from a part into the top are pushed by their source (right-looking, in parallel with
  // the other part); all others are pulled by their target.
  const int first_top = S.part_start[kFactorParts];
  auto pushed = [&](int s, int d) { return d < first_top && s >= first_top; };
  for_each_update([&](int s, int d, int, int, int) {
    if (!pushed(s, d)) ++S.update_start[s + 1];
  });
  for (int s = 0; s < num_super; ++s) S.update_start[s + 1] += S.update_start[s];
  const int pulls = S.update_start[num_super];
  S.update_source.resize(pulls);
  S.update_offset.resize(pulls);
  S.update_count.resize(pulls);
  S.top_offset.assign(first_top, 0);
  for (int d = 0; d < first_top; ++d) S.top_offset[d] = S.row_start[d + 1] - S.row_start[d];
  S.work.assign(num_super, 0.0);
  {
    std::vector<int> fill(S.update_start.begin(), S.update_start.end() - 1);
    for_each_update([&](int s, int d, int offset, int cols, int rows) {
      S.max_update_columns = std::max(S.max_update_columns, cols);
      const double flops = 2.0 * (S.col_start[d + 1] - S.col_start[d]) * cols * rows;
      if (pushed(s, d)) {
        S.top_offset[d] = std::min(S.top_offset[d], offset);
        S.work[d] += flops;
        return;
      }
      const int slot = fill[s]++;
      S.update_source[slot] = d;
      S.update_offset[slot] = offset;
      S.update_count[slot] = cols;
      S.work[s] += flops;
    });
  }
  for (int s = 0; s < num_super; ++s) {
    const double w = S.col_start[s + 1] - S.col_start[s], m = S.row_start[s + 1] - S.row_start[s];
    S.work[s] += w * w * m + m * w;  // the dense factorization and the assembly
  }
  progress.advance(1.0);
  return S;
}

}  // namespace gauss
