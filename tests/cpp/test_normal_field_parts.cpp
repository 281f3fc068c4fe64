// The parts NormalField is built from: the geodesic lattice, the grid of nodes
// within reach, and the Schwarz-preconditioned solve of the regularized Eq. 10.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "gauss/style/kernel_system.h"
#include "gauss/style/node_grid.h"
#include "gauss/util/parallel.h"
#include "gauss/style/sphere_lattice.h"
#include "test_directions.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_normal_field_parts {

namespace {

using Eigen::Vector3d;

using gauss_test::random_directions;

TEST(SphereLattice, HasTheGeodesicCountsNeighboursAndNearestNodes) {
  for (int n : {1, 2, 5, 32}) {
    const gauss::SphereLattice lattice(n);
    ASSERT_EQ(lattice.size(), 10 * n * n + 2) << n;
    int fives = 0;
    for (int i = 0; i < lattice.size(); ++i) {
      EXPECT_NEAR(lattice.nodes()[i].norm(), 1.0, 1e-15);
      const int degree = static_cast<int>(lattice.neighbors_end(i) - lattice.neighbors_begin(i));
      ASSERT_TRUE(degree == 5 || degree == 6) << n << " " << i;
      fives += degree == 5;
      for (const int* j = lattice.neighbors_begin(i); j != lattice.neighbors_end(i); ++j) {
        // neighbours are about one spacing apart, and the relation is symmetric
        EXPECT_LT(std::acos(lattice.nodes()[i].dot(lattice.nodes()[*j])), 1.5 * lattice.mean_spacing());
        EXPECT_TRUE(std::find(lattice.neighbors_begin(*j), lattice.neighbors_end(*j), i) != lattice.neighbors_end(*j));
      }
    }
    EXPECT_EQ(fives, 12) << n;  // the icosahedron's vertices
    for (const Vector3d& x : random_directions(2000, n)) {
      int best = 0;
      for (int i = 1; i < lattice.size(); ++i)
        if (x.dot(lattice.nodes()[i]) > x.dot(lattice.nodes()[best])) best = i;
      EXPECT_EQ(lattice.nearest(x), best) << n;
    }
  }
  EXPECT_EQ(gauss::SphereLattice::frequency_for_spacing(10.0), 1);
  EXPECT_LE(gauss::SphereLattice(gauss::SphereLattice::frequency_for_spacing(0.05)).mean_spacing(), 0.05);
  EXPECT_GT(gauss::SphereLattice(gauss::SphereLattice::frequency_for_spacing(0.05) - 1).mean_spacing(), 0.05);
  EXPECT_THROW(gauss::SphereLattice(0), std::invalid_argument);
  EXPECT_THROW(gauss::SphereLattice(gauss::SphereLattice::kMaxFrequency + 1), std::invalid_argument);
}

TEST(NodeGrid, ListsEveryNodeWithinReachInOrderAndRespectsItsBudget) {
  const std::vector<Vector3d> nodes = random_directions(3000, 2);
  for (double reach : {0.05, 0.3, 1.5, 2.5}) {
    gauss::NodeGrid grid(reach);
    ASSERT_TRUE(grid.build(nodes, SIZE_MAX));
    for (const Vector3d& x : random_directions(500, 3)) {
      const int c = grid.cell(x);
      EXPECT_TRUE(std::is_sorted(grid.begin(c), grid.end(c)));
      for (int j = 0; j < static_cast<int>(nodes.size()); ++j)
        if ((nodes[j] - x).norm() <= reach)
          EXPECT_TRUE(std::binary_search(grid.begin(c), grid.end(c), j)) << reach << " " << j;
    }
    EXPECT_FALSE(grid.build(nodes, grid.entries() - 1));  // over budget: refused, lists kept
    EXPECT_GT(grid.entries(), 0u);
  }
}

// Against a dense Cholesky solve of the same truncated system, for a cluster of close nodes (the
// ill-conditioned case the preconditioner exists for), with and without a right-hand side, and with
// the same bits on one thread as on two.
TEST(KernelSystem, SolvesTheRegularizedSystemLikeADenseSolver) {
  std::vector<Vector3d> nodes = random_directions(600, 4);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 200; ++i)  // a tight bunch: nodes a fraction of a kernel width apart
    nodes.push_back((Vector3d(0, 0, 1) + 0.02 * Vector3d(normal(rng), normal(rng), normal(rng))).normalized());
  const double sigma = 300, ridge = 1e-4, cutoff = 1.0 - std::log(1e7) / sigma;
  const int M = static_cast<int>(nodes.size());
  gauss::NodeGrid grid(std::sqrt(2.0 * (1.0 - cutoff)));
  ASSERT_TRUE(grid.build(nodes, SIZE_MAX));
  std::vector<std::vector<int>> patches;  // every node with its 20 nearest
  for (int i = 0; i < M; ++i) {
    std::vector<int> p(M);
    for (int j = 0; j < M; ++j) p[j] = j;
    std::partial_sort(p.begin(), p.begin() + 20, p.end(),
                      [&](int a, int b) { return nodes[a].dot(nodes[i]) > nodes[b].dot(nodes[i]); });
    p.resize(20);
    patches.push_back(p);
  }
  Eigen::MatrixXd A(M, M);
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < M; ++j) {
      const double t = nodes[i].dot(nodes[j]);
      A(i, j) = (t >= cutoff ? std::exp(sigma * (t - 1.0)) : 0.0) + (i == j ? ridge : 0.0);
    }
  const Eigen::LLT<Eigen::MatrixXd> dense(A);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(M);
  for (int i = 0; i < M; i += 3) b[i] = 0.5;
  for (bool ones : {true, false}) {
    const Eigen::VectorXd exact = dense.solve(ones ? Eigen::VectorXd::Ones(M) : b);
    std::vector<double> rhs;
    if (!ones) rhs.assign(b.data(), b.data() + M);
    std::vector<double> w_one, w_two;
    for (int threads : {1, 2}) {
      gauss::parallel::ScopedThreads scope(threads);
      gauss::KernelSystem system(nodes, sigma, cutoff, ridge, grid, patches);
      std::vector<double> w = system.shepard();
      const double residual = system.solve(w, rhs, 1e-9, 500);
      EXPECT_LE(residual, 1e-9);
      EXPECT_LT(system.iterations(), 200);
      double worst = 0;
      for (int i = 0; i < M; ++i) worst = std::max(worst, std::abs(w[i] - exact[i]));
      // |dw| <= |(A + ridge I)^-1| |residual|_2 <= sqrt(M) max|residual| / ridge
      EXPECT_LE(worst, std::sqrt(M) * 1e-9 / ridge) << "weights off by " << worst;
      (threads == 1 ? w_one : w_two) = w;
    }
    EXPECT_EQ(w_one, w_two);
  }
}

}  // namespace

}  // namespace test_normal_field_parts
