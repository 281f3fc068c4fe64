#include "gauss/sparse/graph_bisection.h"

#include <algorithm>
#include <queue>

namespace gauss {
namespace {

constexpr int kCoarsest = 120;    // coarsen until the graph has about this many vertices
constexpr double kMaxSide = 0.6;  // each part at most this share of the total weight
constexpr int kPasses = 8;        // refinement passes per level at most (each must improve)
constexpr int kInitialTries = 8;  // level structures tried on the coarsest graph

// Heavy-edge matching: each vertex, least connected first, merges with its unmatched neighbour
// across the heaviest edge. cmap (g.n): fine vertex -> coarse vertex.
WeightedGraph coarsen(const WeightedGraph& g, std::vector<int>& cmap) {
  const int n = g.n;
  long long total = 0;
  for (int w : g.weight) total += w;
  // No coarse vertex may outweigh a few percent of the graph, or no balanced split would exist.
  const long long max_weight = std::max(1LL, static_cast<long long>(1.5 * total / kCoarsest));
  int max_degree = 0;
  for (int v = 0; v < n; ++v) max_degree = std::max(max_degree, g.start[v + 1] - g.start[v]);
  std::vector<int> by_degree(max_degree + 2, 0), order(n);
  for (int v = 0; v < n; ++v) ++by_degree[g.start[v + 1] - g.start[v] + 1];
  for (int d = 0; d <= max_degree; ++d) by_degree[d + 1] += by_degree[d];
  for (int v = 0; v < n; ++v) order[by_degree[g.start[v + 1] - g.start[v]]++] = v;
  std::vector<int> match(n, -1);
  for (int v : order) {
    if (match[v] >= 0) continue;
    int best = -1, best_weight = -1;
    for (int k = g.start[v]; k < g.start[v + 1]; ++k) {
      const int u = g.adj[k];
      if (match[u] >= 0 || g.weight[v] + g.weight[u] > max_weight) continue;
      if (g.edge_weight[k] > best_weight || (g.edge_weight[k] == best_weight && u < best))
        best = u, best_weight = g.edge_weight[k];
    }
    match[v] = best >= 0 ? best : v;
    if (best >= 0) match[best] = v;
  }
  cmap.assign(n, -1);
  std::vector<int> members;  // two fine vertices per coarse vertex (the same one twice if unmatched)
  for (int v = 0; v < n; ++v)
    if (cmap[v] < 0) {
      cmap[v] = cmap[match[v]] = static_cast<int>(members.size() / 2);
      members.push_back(v);
      members.push_back(match[v]);
    }
  WeightedGraph c;
  c.n = static_cast<int>(members.size() / 2);
  c.start.assign(c.n + 1, 0);
  c.weight.resize(c.n);
  c.adj.reserve(g.adj.size());
  c.edge_weight.reserve(g.adj.size());
  std::vector<int> slot(c.n, -1);  // coarse neighbour -> its entry in the current adjacency list
  for (int cv = 0; cv < c.n; ++cv) {
    const int a = members[2 * cv], b = members[2 * cv + 1];
    c.weight[cv] = g.weight[a] + (b != a ? g.weight[b] : 0);
    const size_t first = c.adj.size();
    for (int x : {a, b}) {
      for (int k = g.start[x]; k < g.start[x + 1]; ++k) {
        const int cu = cmap[g.adj[k]];
        if (cu == cv) continue;
        if (slot[cu] < 0) {
          slot[cu] = static_cast<int>(c.adj.size());
          c.adj.push_back(cu);
          c.edge_weight.push_back(g.edge_weight[k]);
        } else {
          c.edge_weight[slot[cu]] += g.edge_weight[k];
        }
      }
      if (b == a) break;  // unmatched: one fine vertex
    }
    for (size_t i = first; i < c.adj.size(); ++i) slot[c.adj[i]] = -1;
    c.start[cv + 1] = static_cast<int>(c.adj.size());
  }
  return c;
}

// How good a separator state is: balanced first, then light, then even.
struct Score {
  long long excess;  // weight of the heavier part beyond the limit (0: balanced)
  long long separator;
  long long imbalance;
  bool operator<(const Score& o) const {  // "better than"
    if (excess != o.excess) return excess < o.excess;
    if (separator != o.separator) return separator < o.separator;
    return imbalance < o.imbalance;
  }
};

// Max-heap of vertices by key (ties: the smaller vertex first) whose keys can change.
class GainHeap {
 public:
  explicit GainHeap(int n) : pos_(n, -1), key_(n, 0) {}
  bool empty() const { return heap_.empty(); }
  int top() const { return heap_[0]; }
  int key(int v) const { return key_[v]; }
  bool contains(int v) const { return pos_[v] >= 0; }
  void insert(int v, int key) {
    key_[v] = key;
    pos_[v] = static_cast<int>(heap_.size());
    heap_.push_back(v);
    up(pos_[v]);
  }
  void add(int v, int delta) {
    key_[v] += delta;
    if (delta > 0) up(pos_[v]);
    else down(pos_[v]);
  }
  void remove(int v) {
    const int i = pos_[v], last = heap_.back();
    heap_.pop_back();
    pos_[v] = -1;
    if (last == v) return;
    heap_[i] = last;
    pos_[last] = i;
    up(i);
    down(pos_[last]);
  }
  void clear() {
    for (int v : heap_) pos_[v] = -1;
    heap_.clear();
  }

 private:
  bool above(int a, int b) const { return key_[a] != key_[b] ? key_[a] > key_[b] : a < b; }
  void place(int v, int i) {
    heap_[i] = v;
    pos_[v] = i;
  }
  void up(int i) {
    const int v = heap_[i];
    for (; i > 0 && above(v, heap_[(i - 1) / 2]); i = (i - 1) / 2) place(heap_[(i - 1) / 2], i);
    place(v, i);
  }
  void down(int i) {
    const int v = heap_[i], n = static_cast<int>(heap_.size());
    for (int c = 2 * i + 1; c < n; i = c, c = 2 * i + 1) {
      if (c + 1 < n && above(heap_[c + 1], heap_[c])) ++c;
      if (!above(heap_[c], v)) break;
      place(heap_[c], i);
    }
    place(v, i);
  }
  std::vector<int> heap_, pos_, key_;
};

// Fiduccia-Mattheyses refinement of a vertex separator. A move takes a separator vertex v to part
// `to` and pulls v's neighbours in the other part into the separator; its gain is the separator
// weight it saves. Each pass makes the best allowed move again and again (each vertex moves at most
// once), tolerating a run of moves without improvement to climb out of local minima, then rolls
// back to the best state it saw. Gains are kept up to date incrementally in one heap per part.
class Refiner {
 public:
  Refiner(const WeightedGraph& g, std::vector<uint8_t>& side)
      : g_(g), side_(side), locked_(g.n, 0), mark_(g.n, 0), queue_{GainHeap(g.n), GainHeap(g.n)} {
    long long total = 0;
    for (int w : g.weight) total += w;
    limit_ = static_cast<long long>(kMaxSide * total);
    for (int v = 0; v < g.n; ++v) {
      part_weight_[side[v]] += g.weight[v];
      if (side[v] == 2) separator_.push_back(v);
    }
  }

  void refine() {
    for (int pass = 0; pass < kPasses; ++pass) {
      // A run of this many moves without improvement ends the pass (METIS's rule of thumb: about
      // twice the separator, at most a few hundred).
      const int patience = std::clamp(2 * static_cast<int>(separator_.size()), 20, 300);
      for (int v : separator_) insert(v);
      moved_.clear();
      pulled_.clear();
      pulled_end_.clear();
      const Score start = score();
      Score best = start;
      size_t best_moves = 0;
      for (int since_best = 0; since_best < patience; ++since_best) {
        const int to = choose();
        if (to < 0) break;
        move(queue_[to].top(), to);
        if (score() < best) {
          best = score();
          best_moves = moved_.size();
          since_best = -1;
        }
      }
      for (GainHeap& q : queue_) q.clear();
      for (int v : moved_) locked_[v] = 0;
      while (moved_.size() > best_moves) undo();
      // The separator now: the old one without the moved vertices, plus the pulled ones.
      std::vector<int> next;
      for (const std::vector<int>* list : {&separator_, &pulled_})
        for (int v : *list)
          if (side_[v] == 2 && !mark_[v]) {
            mark_[v] = 1;
            next.push_back(v);
          }
      for (int v : next) mark_[v] = 0;
      separator_ = std::move(next);
      if (!(best < start)) break;
    }
  }

 private:
  Score score() const {
    const long long heavy = std::max(part_weight_[0], part_weight_[1]);
    return {std::max(0LL, heavy - limit_), part_weight_[2], std::abs(part_weight_[0] - part_weight_[1])};
  }

  int gain(int v, int to) const {
    int gain = g_.weight[v];
    for (int k = g_.start[v]; k < g_.start[v + 1]; ++k)
      if (side_[g_.adj[k]] == 1 - to) gain -= g_.weight[g_.adj[k]];
    return gain;
  }

  void insert(int v) {
    for (int to = 0; to < 2; ++to) queue_[to].insert(v, gain(v, to));
  }

  // The part the next move goes to, or -1 if no move is allowed. A move into a part may not push it
  // over the limit; while the state is unbalanced only moves into the lighter part count.
  int choose() const {
    bool ok[2];
    for (int to = 0; to < 2; ++to)
      ok[to] = !queue_[to].empty() && part_weight_[to] + g_.weight[queue_[to].top()] <= limit_;
    const int lighter = part_weight_[0] <= part_weight_[1] ? 0 : 1;
    if (score().excess > 0) return ok[lighter] ? lighter : -1;
    if (ok[0] && ok[1]) {
      const int g0 = queue_[0].key(queue_[0].top()), g1 = queue_[1].key(queue_[1].top());
      return g0 != g1 ? (g0 > g1 ? 0 : 1) : lighter;
    }
    return ok[0] ? 0 : (ok[1] ? 1 : -1);
  }

  void move(int v, int to) {
    const int other = 1 - to;
    for (GainHeap& q : queue_) q.remove(v);
    side_[v] = static_cast<uint8_t>(to);
    locked_[v] = 1;
    part_weight_[2] -= g_.weight[v];
    part_weight_[to] += g_.weight[v];
    moved_.push_back(v);
    const size_t first = pulled_.size();
    for (int k = g_.start[v]; k < g_.start[v + 1]; ++k) {
      const int u = g_.adj[k];
      if (side_[u] == other) {
        side_[u] = 2;
        mark_[u] = 1;
        part_weight_[other] -= g_.weight[u];
        part_weight_[2] += g_.weight[u];
        pulled_.push_back(u);
      } else if (side_[u] == 2 && queue_[other].contains(u)) {
        queue_[other].add(u, -g_.weight[v]);  // moving u to `other` would now pull v
      }
    }
    pulled_end_.push_back(pulled_.size());
    // Separator vertices next to a pulled vertex no longer pull it when moving to `to`.
    for (size_t i = first; i < pulled_.size(); ++i)
      for (int k = g_.start[pulled_[i]]; k < g_.start[pulled_[i] + 1]; ++k) {
        const int x = g_.adj[k];
        if (side_[x] == 2 && !mark_[x] && queue_[to].contains(x)) queue_[to].add(x, g_.weight[pulled_[i]]);
      }
    for (size_t i = first; i < pulled_.size(); ++i) {
      mark_[pulled_[i]] = 0;
      if (!locked_[pulled_[i]]) insert(pulled_[i]);
    }
  }

  void undo() {
    const int v = moved_.back(), to = side_[v], other = 1 - to;
    moved_.pop_back();
    pulled_end_.pop_back();
    const size_t first = pulled_end_.empty() ? 0 : pulled_end_.back();
    for (size_t i = first; i < pulled_.size(); ++i) {
      side_[pulled_[i]] = static_cast<uint8_t>(other);
      part_weight_[2] -= g_.weight[pulled_[i]];
      part_weight_[other] += g_.weight[pulled_[i]];
    }
    pulled_.resize(first);
    side_[v] = 2;
    part_weight_[to] -= g_.weight[v];
    part_weight_[2] += g_.weight[v];
  }

  const WeightedGraph& g_;
  std::vector<uint8_t>& side_;
  std::vector<uint8_t> locked_, mark_;
  std::vector<int> separator_;  // the separator's vertices at the start of a pass
  long long part_weight_[3] = {0, 0, 0};
  long long limit_ = 0;
  GainHeap queue_[2];
  std::vector<int> moved_, pulled_;
  std::vector<size_t> pulled_end_;
};

// The separator of a breadth-first level structure from `root` at the level holding the weighted
// median, refined. Depth-1 structures (nearly complete graphs) separate the root from the rest.
std::vector<uint8_t> level_separator(const WeightedGraph& g, int root) {
  std::vector<int> level(g.n, -1), queue(g.n);
  auto bfs = [&](int r) {
    std::fill(level.begin(), level.end(), -1);
    int head = 0, tail = 0;
    queue[tail++] = r;
    level[r] = 0;
    while (head < tail) {
      const int v = queue[head++];
      for (int k = g.start[v]; k < g.start[v + 1]; ++k)
        if (level[g.adj[k]] < 0) {
          level[g.adj[k]] = level[v] + 1;
          queue[tail++] = g.adj[k];
        }
    }
  };
  bfs(root);
  bfs(queue[g.n - 1]);  // restart from a farthest vertex: a pseudo-peripheral root
  const int depth = level[queue[g.n - 1]];
  long long total = 0, below = 0;
  for (int w : g.weight) total += w;
  int cut = 1;
  for (int i = 0; i < g.n; ++i) {
    below += g.weight[queue[i]];
    if (2 * below >= total) {
      cut = std::clamp(level[queue[i]], 1, std::max(1, depth - 1));
      break;
    }
  }
  std::vector<uint8_t> side(g.n);
  for (int v = 0; v < g.n; ++v) side[v] = level[v] < cut ? 0 : (level[v] == cut ? 2 : 1);
  Refiner(g, side).refine();
  return side;
}

}  // namespace

std::vector<uint8_t> vertex_separator(const WeightedGraph& g, const Progress& progress) {
  const std::vector<uint8_t> stopped(g.n, 2);
  std::vector<WeightedGraph> coarse;
  std::vector<std::vector<int>> cmaps;
  const WeightedGraph* current = &g;
  while (current->n > kCoarsest) {
    if (progress.cancelled()) return stopped;
    std::vector<int> cmap;
    WeightedGraph c = coarsen(*current, cmap);
    if (c.n > 0.95 * current->n) break;  // matching stalled (stars and the like)
    coarse.push_back(std::move(c));
    cmaps.push_back(std::move(cmap));
    current = &coarse.back();
  }
  // A few level structures on the coarsest graph, each refined; keep the best.
  const WeightedGraph& top = *current;
  std::vector<uint8_t> side;
  Score best{0, 0, 0};
  for (int t = 0; t < kInitialTries; ++t) {
    std::vector<uint8_t> candidate = level_separator(top, static_cast<int>(int64_t{top.n} * t / kInitialTries));
    long long w[3] = {0, 0, 0};
    for (int v = 0; v < top.n; ++v) w[candidate[v]] += top.weight[v];
    long long total = w[0] + w[1] + w[2];
    const Score s{std::max(0LL, std::max(w[0], w[1]) - static_cast<long long>(kMaxSide * total)), w[2],
                  std::abs(w[0] - w[1])};
    if (side.empty() || s < best) side = std::move(candidate), best = s;
  }
  // Back to the finest graph, refining at every level.
  for (int level = static_cast<int>(coarse.size()) - 1; level >= 0; --level) {
    if (progress.cancelled()) return stopped;
    const WeightedGraph& finer = level > 0 ? coarse[level - 1] : g;
    std::vector<uint8_t> fine_side(finer.n);
    for (int v = 0; v < finer.n; ++v) fine_side[v] = side[cmaps[level][v]];
    side = std::move(fine_side);
    Refiner(finer, side).refine();
  }
  return side;
}

}  // namespace gauss
