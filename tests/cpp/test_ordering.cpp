// The pieces of the factorization's symbolic side: elimination tree and column counts against a
// brute-force symbolic factorization, the multilevel vertex separator, nested dissection.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "gauss/sparse/elimination_tree.h"
#include "gauss/sparse/graph_bisection.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/sparse/nested_dissection.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_ordering {

namespace {

// Lower triangle (pattern) of a random symmetric matrix with a full diagonal.
Eigen::SparseMatrix<double> random_pattern(int n, int per_row, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> column(0, n - 1);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 1.0);
    for (int k = 0; k < per_row; ++k) {
      const int j = column(rng);
      entries.emplace_back(std::max(i, j), std::min(i, j), 1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Column structures of L by symbolic elimination: struct(L_j) = struct(A_j) + struct(L_c) of its
// children c, minus rows < j.
std::vector<std::set<int>> symbolic_columns(const gauss::LowerColumns& A, const std::vector<int>& parent) {
  std::vector<std::set<int>> columns(A.n);
  for (int j = 0; j < A.n; ++j) {
    columns[j].insert(j);
    for (int p = A.start[j]; p < A.start[j + 1]; ++p) columns[j].insert(A.rows[p]);
  }
  for (int j = 0; j < A.n; ++j)
    if (parent[j] >= 0)
      for (int r : columns[j])
        if (r > j && r >= parent[j]) columns[parent[j]].insert(r);
  return columns;
}

gauss::WeightedGraph mesh_graph(const gauss::TriangleMesh& m) {
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology t = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  gauss::WeightedGraph g;
  g.n = m.num_vertices();
  std::vector<std::vector<int>> neighbours(g.n);
  for (const auto& e : t.edges) {
    neighbours[e[0]].push_back(e[1]);
    neighbours[e[1]].push_back(e[0]);
  }
  g.start.push_back(0);
  for (const auto& list : neighbours) {
    g.adj.insert(g.adj.end(), list.begin(), list.end());
    g.start.push_back(static_cast<int>(g.adj.size()));
  }
  g.edge_weight.assign(g.adj.size(), 1);
  g.weight.assign(g.n, 1);
  return g;
}

}  // namespace

TEST(EliminationTree, TreeAndColumnCountsMatchSymbolicElimination) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Eigen::SparseMatrix<double> A = random_pattern(120, seed % 3, seed);
    std::vector<int> identity(120);
    for (int i = 0; i < 120; ++i) identity[i] = i;
    const gauss::LowerColumns given = gauss::permute_lower(A, identity, false);
    const std::vector<int> given_parent = gauss::elimination_tree(given);
    // Renumber in postorder, as the analysis does, then count.
    const std::vector<int> post = gauss::postorder(given_parent);
    ASSERT_EQ(post.size(), 120u);
    std::vector<int> new_of_old(120);
    for (int k = 0; k < 120; ++k) new_of_old[post[k]] = k;
    const gauss::LowerColumns P = gauss::permute_lower(A, new_of_old, false);
    const std::vector<int> parent = gauss::elimination_tree(P);
    const std::vector<std::set<int>> columns = symbolic_columns(P, parent);
    const std::vector<int> counts = gauss::column_counts(P, parent);
    for (int j = 0; j < 120; ++j) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", column " + std::to_string(j));
      // The parent is the first row below the diagonal of the column.
      const auto below = columns[j].upper_bound(j);
      EXPECT_EQ(parent[j], below == columns[j].end() ? -1 : *below);
      EXPECT_EQ(counts[j], static_cast<int>(columns[j].size()));
      if (parent[j] >= 0) EXPECT_EQ(parent[j], new_of_old[given_parent[post[j]]]);
    }
  }
}

TEST(GraphBisection, SeparatorSeparatesAndBalances) {
  for (int levels : {2, 4, 5}) {
    const gauss::WeightedGraph g = mesh_graph(gauss_test::icosphere(levels));
    const std::vector<uint8_t> side = gauss::vertex_separator(g, gauss::Progress());
    int size[3] = {0, 0, 0};
    for (uint8_t s : side) ++size[s];
    SCOPED_TRACE("vertices " + std::to_string(g.n));
    for (int v = 0; v < g.n; ++v)
      for (int k = g.start[v]; k < g.start[v + 1]; ++k)
        ASSERT_FALSE((side[v] == 0 && side[g.adj[k]] == 1) || (side[v] == 1 && side[g.adj[k]] == 0));
    EXPECT_LE(std::max(size[0], size[1]), 0.61 * g.n);
    EXPECT_GT(std::min(size[0], size[1]), 0);
    // A sphere's best separators are great circles: about 2 pi r edges for 4 pi r^2 / sqrt(3) vertices.
    EXPECT_LT(size[2], 4.0 * std::sqrt(double(g.n)));
  }
}

TEST(NestedDissection, IsAPermutationAndIsDeterministic) {
  const gauss::WeightedGraph g = mesh_graph(gauss_test::grid_cube(100));  // above the AMD-only size
  gauss::Progress progress;
  progress.start(gauss::SetupPhase::ordering);
  const std::vector<int> order = gauss::nested_dissection(g.n, g.start, g.adj, progress);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < g.n; ++i) ASSERT_EQ(sorted[i], i);
  EXPECT_EQ(gauss::nested_dissection(g.n, g.start, g.adj, progress), order);
}

}  // namespace test_ordering
