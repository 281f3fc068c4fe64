// Fill of the Cholesky factor of a mesh Laplacian with the nested-dissection ordering
// (nested_dissection.h) against approximate minimum degree (Eigen's AMDOrdering), on the shared test
// meshes. The counts are exact: nonzeros of L (diagonal included) from the column counts of the
// ordered pattern (elimination_tree.h), no numeric factorization needed.
//
// What nested_dissection.h promises: graphs of at most 50,000 vertices are ordered by AMD itself, so
// on the shared meshes (35K bunny, 43K armadillo) the two fills are equal; above that, dissection gives
// the sparser factor on the bunny subdivided once (1:4, still a scanned surface, not a synthetic grid),
// though not on every mesh (docs/performance.md#set-up-at-scale).
#include <gtest/gtest.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "gauss/sparse/elimination_tree.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/sparse/nested_dissection.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_fill_nested_dissection {

namespace {

// nested_dissection.h: graphs up to this size are ordered by AMD alone.
constexpr int kAmdOnlyVertices = 50000;

// Every triangle split into four at its edge midpoints.
gauss::TriangleMesh subdivided(const gauss::TriangleMesh& m) {
  gauss::TriangleMesh out = m;
  out.F.clear();
  std::map<std::pair<int64_t, int64_t>, int64_t> midpoint;
  auto mid = [&](int64_t a, int64_t b) {
    const auto key = std::minmax(a, b);
    const auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    for (int k = 0; k < 3; ++k) out.V.push_back(0.5 * (m.V[3 * a + k] + m.V[3 * b + k]));
    return midpoint[key] = static_cast<int64_t>(out.V.size() / 3) - 1;
  };
  for (int f = 0; f < m.num_faces(); ++f) {
    const int64_t a = m.F[3 * f], b = m.F[3 * f + 1], c = m.F[3 * f + 2];
    const int64_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    out.F.insert(out.F.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
  }
  return out;
}

struct Graph {
  int n = 0;
  std::vector<int> start, adj;
  Eigen::SparseMatrix<double> lower;      // pattern of the Laplacian, lower triangle with diagonal
  Eigen::SparseMatrix<double> symmetric;  // the same, both triangles
};

Graph laplacian_graph(const gauss::TriangleMesh& m) {
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology t = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  Graph g;
  g.n = m.num_vertices();
  std::vector<std::vector<int>> neighbours(g.n);
  std::vector<Eigen::Triplet<double>> lower, both;
  for (const auto& e : t.edges) {
    neighbours[e[0]].push_back(e[1]);
    neighbours[e[1]].push_back(e[0]);
    lower.emplace_back(std::max(e[0], e[1]), std::min(e[0], e[1]), 1.0);
    both.emplace_back(e[0], e[1], 1.0);
    both.emplace_back(e[1], e[0], 1.0);
  }
  for (int v = 0; v < g.n; ++v) {
    lower.emplace_back(v, v, 1.0);
    both.emplace_back(v, v, 1.0);
  }
  g.start.push_back(0);
  for (const auto& list : neighbours) {
    g.adj.insert(g.adj.end(), list.begin(), list.end());
    g.start.push_back(static_cast<int>(g.adj.size()));
  }
  g.lower.resize(g.n, g.n);
  g.lower.setFromTriplets(lower.begin(), lower.end());
  g.symmetric.resize(g.n, g.n);
  g.symmetric.setFromTriplets(both.begin(), both.end());
  return g;
}

// Nonzeros of L for the ordering old_of_new (vertex eliminated k-th), diagonal included. The counts
// need a postordered numbering; a postorder of the elimination tree keeps the fill.
long long factor_nonzeros(const Graph& g, const std::vector<int>& old_of_new) {
  std::vector<int> new_of_old(g.n);
  for (int k = 0; k < g.n; ++k) new_of_old[old_of_new[k]] = k;
  const std::vector<int> post = gauss::postorder(gauss::elimination_tree(gauss::permute_lower(g.lower, new_of_old, false)));
  std::vector<int> position(g.n);
  for (int k = 0; k < g.n; ++k) position[post[k]] = k;
  for (int& p : new_of_old) p = position[p];
  const gauss::LowerColumns P = gauss::permute_lower(g.lower, new_of_old, false);
  long long total = 0;
  for (int c : gauss::column_counts(P, gauss::elimination_tree(P))) total += c;
  return total;
}

struct Fill {
  long long nested_dissection, amd;
};

Fill measure(const std::string& name, const gauss::TriangleMesh& mesh) {
  const Graph g = laplacian_graph(mesh);
  gauss::Progress progress;
  progress.start(gauss::SetupPhase::ordering);
  const std::vector<int> nd = gauss::nested_dissection(g.n, g.start, g.adj, progress);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(g.symmetric, amd);  // amd.indices()[k]: the vertex eliminated k-th
  const std::vector<int> amd_order(amd.indices().data(), amd.indices().data() + g.n);
  const Fill fill{factor_nonzeros(g, nd), factor_nonzeros(g, amd_order)};
  std::printf("[ fill     ] %s: %d vertices, nnz(L) nested dissection %lld, AMD %lld (ratio %.3f)\n", name.c_str(),
              g.n, fill.nested_dissection, fill.amd, double(fill.nested_dissection) / double(fill.amd));
  return fill;
}

const char* const kMeshes[] = {"bunny/bun_zipper_35947.obj", "bunny/bunny_watertight_34834.obj",
                               "armadillo/armadillo_libigl_43243.obj"};

bool have(const std::string& rel) { return static_cast<bool>(std::ifstream(gauss_test::shared_mesh(rel))); }

}  // namespace

TEST(NestedDissectionFill, SharedMeshesUpTo50KAreOrderedAsByAmd) {
  for (const char* rel : kMeshes) {
    if (!have(rel)) GTEST_SKIP() << "../shared/meshes not present";
    const gauss::TriangleMesh mesh = gauss::read_mesh(gauss_test::shared_mesh(rel));
    ASSERT_LE(mesh.num_vertices(), kAmdOnlyVertices);
    const Fill fill = measure(rel, mesh);
    EXPECT_LE(fill.nested_dissection, fill.amd) << rel;
  }
}

// Checks one mesh subdivided once, above the AMD-only size.
void expect_sparser_than_amd(const char* rel) {
  if (!have(rel)) GTEST_SKIP() << "../shared/meshes not present";
  const gauss::TriangleMesh mesh = subdivided(gauss::read_mesh(gauss_test::shared_mesh(rel)));
  ASSERT_GT(mesh.num_vertices(), kAmdOnlyVertices);
  const Fill fill = measure(std::string(rel) + " subdivided", mesh);
  EXPECT_LT(fill.nested_dissection, fill.amd) << rel;
}

TEST(NestedDissectionFill, SubdividedBunnyIsSparserThanAmd) { expect_sparser_than_amd("bunny/bunny_watertight_34834.obj"); }

}  // namespace test_fill_nested_dissection
