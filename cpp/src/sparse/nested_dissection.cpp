#include "gauss/sparse/nested_dissection.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>

#include "gauss/sparse/graph_bisection.h"
#include "gauss/util/parallel.h"

namespace gauss {
namespace {

// Pieces of at most this many vertices, and whole graphs of at most kSmallGraph, are ordered by
// approximate minimum degree, which at these sizes saves the time of further dissection at little or
// no cost in fill (measured: docs/performance.md#set-up-at-scale).
constexpr int kLeafSize = 1000;
constexpr int kSmallGraph = 50000;
// Pieces split level by level before each is ordered on its own (the results do not depend on it).
constexpr int kTopPieces = 8;

struct Piece {
  int begin, end;  // positions in the permutation; the piece's vertices carry label begin
};

class Dissection {
 public:
  Dissection(int n, const int* start, const int* adj, Progress& progress)
      : start_(start), adj_(adj), progress_(progress), perm_(n), label_(n, 0), local_(n, -1) {
    for (int i = 0; i < n; ++i) perm_[i] = i;
    // Every level of dissection touches each vertex once; the leaves' AMD costs about two levels.
    // Counted, not std::log2: log2@GLIBC_2.29 would raise the module's glibc floor (test_module_reach.py).
    int levels = 0;
    for (double pieces = double(n) / kLeafSize; pieces > 1.0; pieces /= 2) ++levels;
    total_work_ = std::max(1.0, double(n) * (2.0 + levels));
  }

  // Orders `root` and every piece below it. scratch: capacity >= the piece's size.
  void order(Piece root, std::vector<int>& scratch) {
    std::vector<Piece> stack{root};
    while (!stack.empty() && !progress_.cancelled()) {
      const Piece p = stack.back();
      stack.pop_back();
      split(p, scratch.data(), stack);
    }
  }

  // Orders a leaf completely; otherwise moves the piece's separator to its end, or splits it into
  // its connected components, and appends the pieces that remain to `out`.
  void split(Piece p, int* scratch, std::vector<Piece>& out) {
    const int b = p.begin, m = p.end - p.begin;
    if (m <= kLeafSize) {
      order_leaf(p, scratch);
      report(2 * m);
      return;
    }
    report(m);
    for (int i = b; i < p.end; ++i) local_[perm_[i]] = -1;
    const int reached = bfs(b, perm_[b], scratch, 0);
    if (reached < m) return split_components(p, scratch, reached, out);
    // The piece's own graph in local numbers, then its separator.
    WeightedGraph g;
    g.n = m;
    for (int i = 0; i < m; ++i) local_[perm_[b + i]] = i;
    g.start.reserve(m + 1);
    g.start.push_back(0);
    for (int i = 0; i < m; ++i) {
      const int v = perm_[b + i];
      for (int k = start_[v]; k < start_[v + 1]; ++k)
        if (label_[adj_[k]] == b) g.adj.push_back(local_[adj_[k]]);
      g.start.push_back(static_cast<int>(g.adj.size()));
    }
    g.edge_weight.assign(g.adj.size(), 1);
    g.weight.assign(m, 1);
    const std::vector<uint8_t> side = vertex_separator(g, progress_);
    // Both parts first, the separator last; each keeps its vertices' order.
    int size[3] = {0, 0, 0};
    for (int i = 0; i < m; ++i) ++size[side[i]];
    int fill[3] = {b, b + size[0], b + size[0] + size[1]};
    const int label_of_side[3] = {b, b + size[0], -1};
    for (int i = 0; i < m; ++i) scratch[i] = perm_[b + i];
    for (int i = 0; i < m; ++i) {
      perm_[fill[side[i]]++] = scratch[i];
      label_[scratch[i]] = label_of_side[side[i]];
    }
    if (size[0] > 0) out.push_back({b, b + size[0]});
    if (size[1] > 0) out.push_back({b + size[0], b + size[0] + size[1]});
  }

  // Approximate minimum degree (Eigen's AMD) on the piece's own graph (the piece may be disconnected).
  void order_leaf(Piece p, int* scratch) {
    const int m = p.end - p.begin;
    for (int i = 0; i < m; ++i) local_[perm_[p.begin + i]] = i;
    // The pattern with its diagonal: Eigen's AMD counts it (without it the ordering is useless).
    int entries = m;
    for (int i = p.begin; i < p.end; ++i)
      for (int k = start_[perm_[i]]; k < start_[perm_[i] + 1]; ++k) entries += label_[adj_[k]] == p.begin;
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(m, m);
    pattern.resizeNonZeros(entries);
    int* column = pattern.outerIndexPtr();
    int* row = pattern.innerIndexPtr();
    column[0] = 0;
    for (int i = 0; i < m; ++i) {
      const int v = perm_[p.begin + i];
      column[i + 1] = column[i];
      row[column[i + 1]++] = i;
      for (int k = start_[v]; k < start_[v + 1]; ++k)
        if (label_[adj_[k]] == p.begin) row[column[i + 1]++] = local_[adj_[k]];
    }
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
    Eigen::internal::minimum_degree_ordering(pattern, amd);  // amd.indices()[k]: local vertex k-th
    for (int k = 0; k < m; ++k) scratch[k] = perm_[p.begin + k];
    for (int k = 0; k < m; ++k) perm_[p.begin + k] = scratch[amd.indices()[k]];
    for (int i = p.begin; i < p.end; ++i) label_[perm_[i]] = -1;
  }

  std::vector<int>& permutation() { return perm_; }

 private:
  // Breadth-first search within the piece labelled `label` from `root` (whose local_ must be -1, like
  // every unvisited vertex of the piece); appends to queue[tail..]. Returns the new tail.
  int bfs(int label, int root, int* queue, int tail) {
    int head = tail;
    queue[tail++] = root;
    local_[root] = 0;
    while (head < tail) {
      const int v = queue[head++];
      for (int k = start_[v]; k < start_[v + 1]; ++k) {
        const int u = adj_[k];
        if (label_[u] == label && local_[u] < 0) {
          local_[u] = 0;
          queue[tail++] = u;
        }
      }
    }
    return tail;
  }

  // A disconnected piece becomes one piece per connected component (in the order they are found).
  void split_components(Piece p, int* queue, int tail, std::vector<Piece>& out) {
    std::vector<int> component_end{tail};
    for (int i = p.begin; i < p.end; ++i)
      if (local_[perm_[i]] < 0) component_end.push_back(tail = bfs(p.begin, perm_[i], queue, tail));
    int begin = 0;
    for (int end : component_end) {
      for (int i = begin; i < end; ++i) {
        perm_[p.begin + i] = queue[i];
        label_[queue[i]] = p.begin + begin;
      }
      out.push_back({p.begin + begin, p.begin + end});
      begin = end;
    }
  }

  void report(int work) {
    const double done = done_.fetch_add(work, std::memory_order_relaxed) + work;
    progress_.advance(done / total_work_);
  }

  const int* start_;
  const int* adj_;
  Progress& progress_;
  std::vector<int> perm_;   // positions -> vertices; a piece is a range of it
  std::vector<int> label_;  // vertex -> begin of its piece, -1 once it has its final position
  std::vector<int> local_;  // scratch per vertex (pieces are disjoint, so threads never share it)
  std::atomic<long long> done_{0};
  double total_work_ = 1;
};

}  // namespace

std::vector<int> nested_dissection(int n, const std::vector<int>& adj_start, const std::vector<int>& adj,
                                   Progress& progress) {
  Dissection d(n, adj_start.data(), adj.data(), progress);
  if (n <= kSmallGraph) {
    std::vector<int> scratch(n);
    d.order_leaf({0, n}, scratch.data());
    progress.advance(1.0);
    return std::move(d.permutation());
  }
  // Level by level, every piece of a level on the pool at once, until there are kTopPieces; then
  // each of those with everything below it. Two pieces never share a vertex, and a piece's vertices
  // only neighbour its own or separator vertices, which no thread writes any more, so the threads
  // need no synchronization (and each piece is ordered the same whichever thread takes it).
  std::vector<Piece> pending{{0, n}};
  std::vector<std::exception_ptr> failure;
  auto run = [&](int tasks, auto&& task) {
    failure.assign(tasks, nullptr);
    parallel::for_tasks(tasks, n > 20000, [&](int t) {
      try {
        task(t);
      } catch (...) {
        failure[t] = std::current_exception();
      }
    });
    for (const std::exception_ptr& e : failure)
      if (e) std::rethrow_exception(e);
    progress.check();
  };
  // Biggest first: for_tasks deals tasks round-robin, which then balances the threads.
  auto biggest_first = [](const Piece& a, const Piece& b) { return a.end - a.begin > b.end - b.begin; };
  while (static_cast<int>(pending.size()) < kTopPieces &&
         std::any_of(pending.begin(), pending.end(), [](const Piece& p) { return p.end - p.begin > kLeafSize; })) {
    std::stable_sort(pending.begin(), pending.end(), biggest_first);
    const int tasks = static_cast<int>(pending.size());
    std::vector<std::vector<Piece>> children(tasks);
    std::vector<std::vector<int>> scratches(tasks);
    for (int t = 0; t < tasks; ++t) scratches[t].resize(pending[t].end - pending[t].begin);
    run(tasks, [&](int t) { d.split(pending[t], scratches[t].data(), children[t]); });
    pending.clear();
    for (const std::vector<Piece>& c : children) pending.insert(pending.end(), c.begin(), c.end());
  }
  std::stable_sort(pending.begin(), pending.end(), biggest_first);
  const int tasks = static_cast<int>(pending.size());
  std::vector<std::vector<int>> scratches(tasks);
  for (int t = 0; t < tasks; ++t) scratches[t].resize(pending[t].end - pending[t].begin);
  run(tasks, [&](int t) { d.order(pending[t], scratches[t]); });
  return std::move(d.permutation());
}

}  // namespace gauss
