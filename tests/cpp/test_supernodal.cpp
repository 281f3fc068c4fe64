// The supernodal Cholesky factorization's two halves on small matrices, against dense references:
// the symbolic analysis (supernodal_analysis.h) against a dense symbolic elimination of the same
// pattern, and the numeric factor (supernodal_factor.h) against Eigen's dense LLT and LDLT.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "gauss/mesh/mesh_topology.h"
#include "gauss/sparse/supernodal_analysis.h"
#include "gauss/sparse/supernodal_factor.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_supernodal {

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Dense = Eigen::MatrixXd;
using Pattern = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

// Lower triangle of a random SPD matrix (diagonally dominant) whose off-diagonal entries are chosen by
// `linked(i, j)` for i > j, with random values in [-1, 1].
template <class Linked>
SpMat random_spd(int n, unsigned seed, Linked linked) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> diagonal(n, 0.5);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i)
      if (linked(i, j, rng)) {
        const double v = value(rng);
        entries.emplace_back(i, j, v);
        diagonal[i] += std::abs(v);
        diagonal[j] += std::abs(v);
      }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, diagonal[i]);
  SpMat A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Graph Laplacian of a mesh (unit weights) with the rows of pinned vertices removed, lower triangle.
SpMat pinned_laplacian(const gauss::TriangleMesh& m, const std::vector<int>& pinned) {
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology t = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  std::vector<int> unknown(m.num_vertices(), 0);
  for (int v : pinned) unknown[v] = -1;
  int n = 0;
  for (int& u : unknown) u = u < 0 ? -1 : n++;
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> diagonal(n, 0.0);
  for (const auto& e : t.edges) {
    const int a = unknown[e[0]], b = unknown[e[1]];
    if (a >= 0) diagonal[a] += 1.0;
    if (b >= 0) diagonal[b] += 1.0;
    if (a >= 0 && b >= 0) entries.emplace_back(std::max(a, b), std::min(a, b), -1.0);
  }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, diagonal[i]);
  SpMat A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

struct Case {
  std::string name;
  SpMat A_lower;
};

// Several sparsity patterns and sizes, including ones that give wide supernodes (dense, arrow) and
// ones with no fill at all (diagonal, tridiagonal), and a mesh Laplacian made definite by pins.
std::vector<Case> cases() {
  std::vector<Case> all;
  for (int n : {1, 2, 7, 40, 150}) {
    all.push_back({"random 5% n=" + std::to_string(n),
                   random_spd(n, 10u + n, [](int, int, std::mt19937& r) { return r() % 20 == 0; })});
    all.push_back({"random 30% n=" + std::to_string(n),
                   random_spd(n, 20u + n, [](int, int, std::mt19937& r) { return r() % 10 < 3; })});
  }
  all.push_back({"diagonal", random_spd(30, 1, [](int, int, std::mt19937&) { return false; })});
  all.push_back({"tridiagonal", random_spd(60, 2, [](int i, int j, std::mt19937&) { return i == j + 1; })});
  all.push_back({"banded 5", random_spd(80, 3, [](int i, int j, std::mt19937&) { return i - j <= 5; })});
  all.push_back({"arrow", random_spd(50, 4, [](int i, int j, std::mt19937&) { return i == 49 || j == 0; })});
  all.push_back({"dense", random_spd(45, 5, [](int, int, std::mt19937&) { return true; })});
  all.push_back({"two blocks", random_spd(70, 6, [](int i, int j, std::mt19937& r) {
                   return (i < 35) == (j < 35) && r() % 4 == 0;
                 })});
  all.push_back({"icosphere(2) Laplacian, 3 pins", pinned_laplacian(gauss_test::icosphere(2), {0, 40, 100})});
  all.push_back({"grid cube(4) Laplacian, 1 pin", pinned_laplacian(gauss_test::grid_cube(4), {5})});
  return all;
}

// A fill-reducing-looking but arbitrary ordering: a random permutation (seeded), so the analysis sees
// orders that are not the identity.
std::vector<int> random_order(int n, unsigned seed) {
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  return order;
}

// P A P^T, dense and symmetric, in the numbering row i of A -> row new_of_old[i].
Dense permuted_dense(const SpMat& A_lower, const std::vector<int>& new_of_old) {
  const int n = static_cast<int>(A_lower.rows());
  Dense P = Dense::Zero(n, n);
  for (int j = 0; j < A_lower.outerSize(); ++j)
    for (SpMat::InnerIterator it(A_lower, j); it; ++it) {
      const int a = new_of_old[it.row()], b = new_of_old[it.col()];
      P(a, b) = P(b, a) = it.value();
    }
  return P;
}

// Structure of L by dense symbolic elimination: L(i, j) is structurally nonzero (i >= j) when A(i, j)
// is, or L(i, k) and L(j, k) are for some k < j.
Pattern symbolic_factor(const Dense& A) {
  const int n = static_cast<int>(A.rows());
  Pattern L = Pattern::Constant(n, n, false);
  for (int j = 0; j < n; ++j)
    for (int i = j; i < n; ++i) L(i, j) = i == j || A(i, j) != 0.0;
  for (int k = 0; k < n; ++k)
    for (int j = k + 1; j < n; ++j)
      if (L(j, k))
        for (int i = j; i < n; ++i) L(i, j) = L(i, j) || L(i, k);
  return L;
}

long long count(const Pattern& L) { return static_cast<long long>(L.count()); }

// L (dense, in the structure's numbering) from the supernodal blocks; entries outside the blocks 0.
Dense dense_factor(const gauss::SupernodalStructure& S, const double* values) {
  Dense L = Dense::Zero(S.n, S.n);
  for (int s = 0; s < S.num_supernodes(); ++s) {
    const int c0 = S.col_start[s], w = S.col_start[s + 1] - c0;
    const int r0 = S.row_start[s], m = S.row_start[s + 1] - r0;
    const double* U = values + S.value_start[s];
    for (int c = 0; c < m; ++c)
      for (int i = 0; i < std::min(w, c + 1); ++i) L(S.rows[r0 + c], c0 + i) = U[i + static_cast<int64_t>(w) * c];
  }
  return L;
}

gauss::SupernodalStructure analyse(const SpMat& A_lower, const std::vector<int>& order) {
  gauss::Progress progress;
  progress.start(gauss::SetupPhase::symbolic);
  return gauss::analyse_supernodal(A_lower, order, progress);
}

}  // namespace

TEST(SupernodalAnalysis, StructureMatchesDenseSymbolicElimination) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const int n = static_cast<int>(c.A_lower.rows());
    const std::vector<int> order = random_order(n, 3u + n);
    const gauss::SupernodalStructure S = analyse(c.A_lower, order);
    ASSERT_EQ(S.n, n);

    // new_of_old is a permutation, and the renumbering keeps the fill of the given ordering.
    std::vector<int> given(n), seen(n, 0);
    for (int k = 0; k < n; ++k) given[order[k]] = k;
    for (int i = 0; i < n; ++i) ++seen.at(S.new_of_old.at(i));
    ASSERT_EQ(std::count(seen.begin(), seen.end(), 1), n);
    const Pattern L = symbolic_factor(permuted_dense(c.A_lower, S.new_of_old));
    EXPECT_EQ(count(L), count(symbolic_factor(permuted_dense(c.A_lower, given))));

    // The supernodes partition the columns in order; each one's rows are ascending, start with its
    // own columns and are exactly the union of the structures of its columns.
    const int ns = S.num_supernodes();
    ASSERT_EQ(S.col_start.front(), 0);
    ASSERT_EQ(S.col_start.back(), n);
    long long stored = 0;
    for (int s = 0; s < ns; ++s) {
      const int c0 = S.col_start[s], c1 = S.col_start[s + 1], w = c1 - c0;
      const int r0 = S.row_start[s], m = S.row_start[s + 1] - r0;
      ASSERT_GT(w, 0);
      ASSERT_GE(m, w);
      for (int k = 0; k < w; ++k) EXPECT_EQ(S.rows[r0 + k], c0 + k);
      for (int k = 1; k < m; ++k) EXPECT_LT(S.rows[r0 + k - 1], S.rows[r0 + k]);
      for (int j = c0; j < c1; ++j) EXPECT_EQ(S.super_of_col[j], s);
      std::vector<int> columns_union;
      for (int i = c0; i < n; ++i)
        if (L.block(i, c0, 1, w).any()) columns_union.push_back(i);
      EXPECT_EQ(std::vector<int>(S.rows.begin() + r0, S.rows.begin() + r0 + m), columns_union) << "supernode " << s;
      EXPECT_EQ(S.value_start[s + 1] - S.value_start[s], static_cast<int64_t>(w) * m);
      // Relaxed supernodes store a few explicit zeros: under 30% of a block (the share the analysis
      // allows the narrowest merged blocks; wider ones are allowed less).
      const long long block_values = static_cast<long long>(w) * m - static_cast<long long>(w) * (w - 1) / 2;
      const long long block_nonzeros = L.block(c0, c0, n - c0, w).count();
      EXPECT_LT(block_values - block_nonzeros, 0.3 * block_values + 1e-9) << "supernode " << s;
      stored += block_values;
    }
    EXPECT_GE(stored, count(L));

    // Fundamental supernodes (column j+1 is j's only child and has j's structure below j) are never
    // split: relaxation only merges them.
    for (int j = 0; j + 1 < n; ++j) {
      bool same_below = L(j + 1, j);
      for (int i = j + 1; i < n && same_below; ++i) same_below = L(i, j) == (i == j + 1 || L(i, j + 1));
      int children = 0;
      for (int k = 0; k <= j; ++k) {
        int parent = -1;
        for (int i = k + 1; i < n && parent < 0; ++i)
          if (L(i, k)) parent = i;
        children += parent == j + 1;
      }
      if (same_below && children == 1) EXPECT_EQ(S.super_of_col[j], S.super_of_col[j + 1]) << "column " << j;
    }

    // The parts are contiguous ranges of supernodes whose rows stay in their own columns or the top.
    ASSERT_EQ(static_cast<int>(S.part_start.size()), gauss::kFactorParts + 1);
    EXPECT_EQ(S.part_start.front(), 0);
    EXPECT_EQ(S.top_col, S.col_start[S.part_start[gauss::kFactorParts]]);
    for (int p = 0; p < gauss::kFactorParts; ++p) {
      const int lo = S.col_start[S.part_start[p]], hi = S.col_start[S.part_start[p + 1]];
      for (int s = S.part_start[p]; s < S.part_start[p + 1]; ++s)
        for (int k = S.row_start[s]; k < S.row_start[s + 1]; ++k)
          EXPECT_TRUE((S.rows[k] >= lo && S.rows[k] < hi) || S.rows[k] >= S.top_col)
              << "part " << p << " supernode " << s << " row " << S.rows[k];
    }
  }
}

TEST(SupernodalFactor, ReproducesTheMatrixAndDenseCholesky) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const int n = static_cast<int>(c.A_lower.rows());
    const gauss::SupernodalStructure S = analyse(c.A_lower, random_order(n, 5u + n));
    gauss::Progress progress;
    progress.start(gauss::SetupPhase::factorizing);
    const gauss::FactorValues values = gauss::factor_supernodal(S, progress);
    const Dense L = dense_factor(S, values.get());
    const Dense PAPt = permuted_dense(c.A_lower, S.new_of_old);
    const double scale = PAPt.cwiseAbs().maxCoeff();

    EXPECT_LT((L * L.transpose() - PAPt).cwiseAbs().maxCoeff(), 1e-13 * scale * n);
    // The Cholesky factor with a positive diagonal is unique: it is Eigen's dense one.
    const Eigen::LLT<Dense> llt(PAPt);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const Dense reference = llt.matrixL();
    EXPECT_LT((L - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.cwiseAbs().maxCoeff() * n);
    EXPECT_GT(L.diagonal().minCoeff(), 0.0);

    // Solutions through L match Eigen's dense LDLT of the unpermuted matrix.
    const Dense A = Dense(SpMat(c.A_lower.selfadjointView<Eigen::Lower>()));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    Eigen::VectorXd pb(n);
    for (int i = 0; i < n; ++i) pb[S.new_of_old[i]] = b[i];
    const Eigen::VectorXd y = L.triangularView<Eigen::Lower>().solve(pb);
    const Eigen::VectorXd px = L.transpose().triangularView<Eigen::Upper>().solve(y);
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = px[S.new_of_old[i]];
    const Eigen::VectorXd expected = A.ldlt().solve(b);
    EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
  }
}

TEST(SupernodalFactor, NotPositiveDefiniteThrows) {
  // A 2 by 2 block [1 2; 2 1] (eigenvalue -1) inside an otherwise fine tridiagonal matrix.
  SpMat A = random_spd(20, 9, [](int i, int j, std::mt19937&) { return i == j + 1; });
  A.coeffRef(11, 10) = 2.0 * std::max(A.coeff(10, 10), A.coeff(11, 11));
  const gauss::SupernodalStructure S = analyse(A, random_order(20, 1));
  gauss::Progress progress;
  progress.start(gauss::SetupPhase::factorizing);
  EXPECT_THROW(gauss::factor_supernodal(S, progress), std::runtime_error);
}

}  // namespace test_supernodal
