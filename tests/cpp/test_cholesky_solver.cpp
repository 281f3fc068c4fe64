// The sparse Cholesky solver (ordering, supernodal factorization, sweeps) against Eigen's
// SimplicialLDLT, its determinism across thread counts, its memory check, cancellation and errors.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <thread>

#include "gauss/sparse/cholesky_solver.h"
#include "gauss/util/memory_budget.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/util/parallel.h"
#include "scoped_env.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_cholesky_solver {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// Graph Laplacian of a mesh with random positive edge weights plus `shift` on the diagonal; rows of
// pinned vertices are removed (their neighbours keep the weight on their diagonal), as the solver does.
SpMat mesh_laplacian(const gauss::TriangleMesh& m, const std::vector<int>& pinned, unsigned seed,
                     double shift = 0.0) {
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology t = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  std::vector<int> unknown(m.num_vertices(), 0);
  for (int v : pinned) unknown[v] = -1;
  int n = 0;
  for (int& u : unknown) u = u < 0 ? -1 : n++;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> diagonal(n, shift);
  for (const auto& e : t.edges) {
    const int a = unknown[e[0]], b = unknown[e[1]];
    const double w = weight(rng);
    if (a >= 0) diagonal[a] += w;
    if (b >= 0) diagonal[b] += w;
    if (a >= 0 && b >= 0) entries.emplace_back(std::max(a, b), std::min(a, b), -w);
  }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, diagonal[i]);
  SpMat A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Random symmetric positive definite matrix (lower triangle): random pattern, diagonally dominant.
SpMat random_spd(int n, int per_row, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> column(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> diagonal(n, 1.0);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < per_row; ++k) {
      const int j = column(rng);
      if (j == i) continue;
      const double v = value(rng);
      entries.emplace_back(std::max(i, j), std::min(i, j), v);
      diagonal[i] += std::abs(v);
      diagonal[j] += std::abs(v);
    }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, diagonal[i]);
  SpMat A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Solves A X = B (B: n by 3, row-major, unknown order) through the solver's elimination order.
std::vector<double> solve(const gauss::CholeskySolver& s, const std::vector<double>& B) {
  const int n = s.size();
  std::vector<double> Y(3 * static_cast<size_t>(n)), X(Y.size());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) Y[3 * s.position(i) + k] = B[3 * i + k];
  s.solve_ordered_in_place(Y.data());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) X[3 * i + k] = Y[3 * s.position(i) + k];
  return X;
}

std::vector<double> right_hand_side(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> B(3 * static_cast<size_t>(n));
  for (double& b : B) b = value(rng);
  return B;
}

// Largest relative residual of the three columns, and largest difference to Eigen's SimplicialLDLT
// relative to the solution's size.
void expect_matches_eigen(const SpMat& A_lower, const gauss::CholeskySolver& s, double tolerance) {
  const int n = static_cast<int>(A_lower.rows());
  ASSERT_EQ(s.size(), n);
  const std::vector<double> B = right_hand_side(n, 7);
  const std::vector<double> X = solve(s, B);
  const SpMat A = A_lower.selfadjointView<Eigen::Lower>();
  Eigen::SimplicialLDLT<SpMat> reference(A);
  ASSERT_EQ(reference.info(), Eigen::Success);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd b(n), x(n);
    for (int i = 0; i < n; ++i) b[i] = B[3 * i + k], x[i] = X[3 * i + k];
    const Eigen::VectorXd expected = reference.solve(b);
    EXPECT_LT((A * x - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff(), tolerance) << "column " << k;
    EXPECT_LT((x - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff(), 1e3 * tolerance)
        << "column " << k;
  }
}

}  // namespace

TEST(CholeskySolver, RandomSpdSystemsMatchSimplicialLDLT) {
  for (int n : {1, 2, 17, 300, 1500}) {
    for (int per_row : {0, 1, 4}) {
      const SpMat A = random_spd(n, per_row, 11u * n + per_row);
      gauss::CholeskySolver s;
      s.factor(A);
      SCOPED_TRACE("n " + std::to_string(n) + ", per row " + std::to_string(per_row));
      expect_matches_eigen(A, s, 1e-12);
    }
  }
}

TEST(CholeskySolver, MeshLaplaciansWithPinsMatchSimplicialLDLT) {
  // Small meshes take the minimum-degree path, the 60,002-vertex cube the nested-dissection one.
  const gauss::TriangleMesh small = gauss_test::icosphere(4), large = gauss_test::grid_cube(100);
  for (const gauss::TriangleMesh* m : {&small, &large}) {
    const std::vector<int> pins = {0, 5, m->num_vertices() / 2, m->num_vertices() - 1};
    const SpMat A = mesh_laplacian(*m, pins, 3);
    gauss::CholeskySolver s;
    s.factor(A);
    SCOPED_TRACE("vertices " + std::to_string(m->num_vertices()));
    expect_matches_eigen(A, s, 1e-10);
    EXPECT_GT(s.factor_nonzeros(), A.nonZeros());
  }
}

TEST(CholeskySolver, SinglePrecisionFactorIsRefinedToDoubleAccuracy) {
  // Floats for L's values (what sculpt-sized meshes get), refined once against A: the solution as
  // exact as in doubles to a few digits, one and two threads bit for bit, and a planned solve (not
  // refined) within single precision of the whole one.
  const gauss::TriangleMesh small = gauss_test::icosphere(4), large = gauss_test::grid_cube(100);
  for (const gauss::TriangleMesh* m : {&small, &large}) {
    const SpMat A = mesh_laplacian(*m, {0, 5, m->num_vertices() / 2}, 3);
    SCOPED_TRACE("vertices " + std::to_string(m->num_vertices()));
    std::vector<double> X[2];
    for (int threads : {1, 2}) {
      const gauss::parallel::ScopedThreads scoped(threads);
      gauss::CholeskySolver s;
      s.factor(A, nullptr, gauss::CholeskySolver::Precision::single_values);
      ASSERT_TRUE(s.single_precision());
      expect_matches_eigen(A, s, 1e-9);
      X[threads - 1] = solve(s, right_hand_side(s.size(), 5));
      if (threads == 2) {
        gauss::CholeskySolver d;
        d.factor(A);
        EXPECT_FALSE(d.single_precision());  // automatic: doubles below kSinglePrecisionUnknowns
        const std::vector<double> exact = solve(d, right_hand_side(s.size(), 5));
        // Unrefined, the single factor's solve is off by 5e-8 to 9e-8 here (its residual 5e-7 to
        // 2e-5): the refinement is what brings both within 1e-9.
        double scale = 0, diff = 0;
        for (size_t i = 0; i < exact.size(); ++i)
          scale = std::max(scale, std::abs(exact[i])), diff = std::max(diff, std::abs(exact[i] - X[1][i]));
        EXPECT_LT(diff / scale, 1e-9);
        const int n = s.size();
        std::vector<double> Y(3 * static_cast<size_t>(n), 0.0);
        const int row = s.position(n / 3);
        for (int k = 0; k < 3; ++k) Y[3 * row + k] = 1.0 + k;
        std::vector<double> whole = Y;
        d.solve_ordered_in_place(whole.data());
        std::vector<int> plan;
        s.plan_sparse(&row, 1, plan);
        s.solve_planned_in_place(Y.data(), plan);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(Y[3 * row + k], whole[3 * row + k], 1e-6 * std::abs(whole[3 * row + k]));
      }
    }
    EXPECT_EQ(std::memcmp(X[0].data(), X[1].data(), X[0].size() * sizeof(double)), 0);
  }
}

TEST(CholeskySolver, PlannedSolveGivesTheWholeSolveAtItsRows) {
  // A right-hand side nonzero in a few rows (contact springs' forces): the solve restricted to the
  // elimination tree's paths above them gives the whole solve's values there, for part of its cost.
  // Small meshes (one supernode chain) and the nested-dissection path, rows clustered and scattered.
  const gauss::TriangleMesh small = gauss_test::icosphere(3), large = gauss_test::grid_cube(60);
  for (const gauss::TriangleMesh* m : {&small, &large}) {
    const SpMat A = mesh_laplacian(*m, {0, 3}, 11);
    gauss::CholeskySolver s;
    s.factor(A);
    const int n = s.size();
    for (const std::vector<int>& unknowns : {std::vector<int>{7}, std::vector<int>{7, 8, 9, 10, 11, 12},
                                             std::vector<int>{1, n / 3, n / 2, n - 2}}) {
      SCOPED_TRACE("unknowns " + std::to_string(unknowns.size()) + " of " + std::to_string(n));
      std::vector<double> B(3 * static_cast<size_t>(n), 0.0);
      std::vector<int> rows;
      for (int u : unknowns) {
        rows.push_back(s.position(u));
        for (int k = 0; k < 3; ++k) B[3 * u + k] = 1.0 + u % 5 + k;
      }
      const std::vector<double> whole = solve(s, B);
      std::vector<int> plan;
      s.plan_sparse(rows.data(), static_cast<int>(rows.size()), plan);
      EXPECT_TRUE(std::is_sorted(plan.begin(), plan.end()));
      std::vector<double> Y(3 * static_cast<size_t>(n), 0.0);
      for (int u : unknowns)
        for (int k = 0; k < 3; ++k) Y[3 * s.position(u) + k] = B[3 * u + k];
      s.solve_planned_in_place(Y.data(), plan);
      for (int u : unknowns)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(Y[3 * s.position(u) + k], whole[3 * u + k], 1e-12 * std::abs(whole[3 * u + k]) + 1e-14);
      if (m == &large && unknowns.size() < 10) EXPECT_LT(s.plan_nonzeros(plan), s.factor_nonzeros() / 2);
      EXPECT_LE(s.plan_nonzeros(plan), s.factor_nonzeros());
    }
  }
}

TEST(CholeskySolver, PlannedSolveOfManyRowsRunsOnBothPartsAlike) {
  // Many scattered rows (a contact's hundreds of springs): the plan reaches into both parts of the
  // cut, which then run on their own threads. The rows the plan names come out as the whole solve's,
  // bit for bit on one thread and on two, and the rows outside the plan are left as they were.
  const gauss::TriangleMesh m = gauss_test::grid_cube(60);
  const SpMat A = mesh_laplacian(m, {0, 3}, 11);
  gauss::CholeskySolver s;
  s.factor(A);
  const int n = s.size();
  std::vector<double> B(3 * static_cast<size_t>(n), 0.0);
  std::vector<int> rows;
  for (int u = 5; u < n; u += 37) {
    rows.push_back(s.position(u));
    for (int k = 0; k < 3; ++k) B[3 * u + k] = 1.0 + u % 7 + k;
  }
  const std::vector<double> whole = solve(s, B);
  std::vector<int> plan;
  s.plan_sparse(rows.data(), static_cast<int>(rows.size()), plan);
  std::vector<uint8_t> in_plan(n, 0);
  {
    std::vector<int> single(1);
    for (int r = 0; r < n; ++r) {
      single[0] = r;
      std::vector<int> own;
      s.plan_sparse(single.data(), 1, own);
      in_plan[r] = std::binary_search(plan.begin(), plan.end(), own.front());
    }
  }
  ASSERT_TRUE(s.plan_splits(plan)) << "the plan reaches into both parts";
  const int saved = gauss::parallel::max_threads();
  std::vector<std::vector<double>> results;
  for (int threads : {1, 2}) {
    gauss::parallel::set_max_threads(threads);
    std::vector<double> Y(3 * static_cast<size_t>(n), 0.0);
    for (int r = 0; r < n; ++r)
      if (!in_plan[r]) Y[3 * r] = Y[3 * r + 1] = Y[3 * r + 2] = 42.0;  // neither read nor written
    for (int u = 5; u < n; u += 37)
      for (int k = 0; k < 3; ++k) Y[3 * s.position(u) + k] = B[3 * u + k];
    s.solve_planned_in_place(Y.data(), plan);
    for (int u = 5; u < n; u += 37)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(Y[3 * s.position(u) + k], whole[3 * u + k], 1e-12 * std::abs(whole[3 * u + k]) + 1e-14);
    for (int r = 0; r < n; ++r)
      if (!in_plan[r]) EXPECT_EQ(Y[3 * r], 42.0) << r;
    results.push_back(Y);
  }
  gauss::parallel::set_max_threads(saved);
  EXPECT_EQ(std::memcmp(results[0].data(), results[1].data(), results[0].size() * sizeof(double)), 0);
  EXPECT_LT(std::count(in_plan.begin(), in_plan.end(), 1), n) << "the plan leaves rows out";
}

TEST(CholeskySolver, SharedMeshLaplacianMatchesSimplicialLDLT) {
  const std::string path = gauss_test::shared_mesh("bunny/bun_zipper_35947.obj");
  if (!std::ifstream(path)) GTEST_SKIP() << "../shared/meshes not present";
  const gauss::TriangleMesh m = gauss::read_mesh(path);
  // Unreferenced vertices have empty rows: the shift keeps them definite.
  const SpMat A = mesh_laplacian(m, {1, 2, 3}, 5, 1e-3);
  gauss::CholeskySolver s;
  s.factor(A);
  expect_matches_eigen(A, s, 1e-10);
}

TEST(CholeskySolver, DisconnectedAndStarGraphs) {
  // Many components (a mesh whose pieces the ordering must split apart) and one vertex connected to
  // all others (the coarsening cannot match it) on the nested-dissection path.
  const int n = 60000;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 4.0 + (i == 0 ? n : 0));
  for (int i = 1; i < n; ++i) {
    entries.emplace_back(i, 0, -1.0);                             // the star's centre
    if (i % 97 != 0 && i + 1 < n) entries.emplace_back(i + 1, i, -1.0);  // chains of 96
  }
  SpMat A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  gauss::CholeskySolver s;
  s.factor(A);
  expect_matches_eigen(A, s, 1e-10);  // the centre's diagonal is 60,000 times the others
  SpMat chains = A;
  chains.prune([](int row, int col, double) { return col != 0 || row == 0; });
  s.factor(chains);
  expect_matches_eigen(chains, s, 1e-12);
}

TEST(CholeskySolver, OneAndTwoThreadsAreBitIdentical) {
  const SpMat A = mesh_laplacian(gauss_test::grid_cube(100), {0}, 9);
  const std::vector<double> B = right_hand_side(static_cast<int>(A.rows()), 3);
  std::vector<double> X[2];
  std::vector<int> order[2];
  for (int threads : {1, 2}) {
    const gauss::parallel::ScopedThreads scoped(threads);
    gauss::CholeskySolver s;
    s.factor(A);
    X[threads - 1] = solve(s, B);
    for (int i = 0; i < s.size(); ++i) order[threads - 1].push_back(s.position(i));
  }
  EXPECT_EQ(order[0], order[1]);
  ASSERT_EQ(X[0].size(), X[1].size());
  EXPECT_EQ(std::memcmp(X[0].data(), X[1].data(), X[0].size() * sizeof(double)), 0);
}

TEST(CholeskySolver, TooBigForTheMemoryBudgetIsRefusedAndKeepsThePreviousFactor) {
  const SpMat small = mesh_laplacian(gauss_test::icosphere(3), {0}, 1);
  const SpMat large = mesh_laplacian(gauss_test::icosphere(5), {0}, 2);
  gauss::CholeskySolver s;
  s.factor(small);
  {
    const gauss_test::ScopedEnv budget("GAUSS_MEMORY_BUDGET_MB", "1");
    EXPECT_EQ(gauss::available_memory_bytes(), 1 << 20);
    try {
      s.factor(large);
      FAIL() << "a factorization over the budget must be refused";
    } catch (const gauss::OutOfMemory& e) {
      EXPECT_NE(std::string(e.what()).find("memory"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("1 MB"), std::string::npos) << e.what();
    }
  }
  expect_matches_eigen(small, s, 1e-10);  // still the previous system
  s.factor(large);                        // and without the budget the large one fits
  expect_matches_eigen(large, s, 1e-10);
}

TEST(CholeskySolver, MemoryBudgetReadsTheMachine) {
  const int64_t available = gauss::available_memory_bytes();
  EXPECT_GT(available, int64_t{64} << 20);  // any machine that runs the tests has 64 MB free
  EXPECT_THROW(gauss::check_memory(int64_t{1} << 62, "a test"), gauss::OutOfMemory);
  EXPECT_NO_THROW(gauss::check_memory(1024, "a test"));
}

TEST(CholeskySolver, NotPositiveDefiniteIsRefusedAndKeepsThePreviousFactor) {
  const SpMat good = random_spd(200, 3, 1);
  gauss::CholeskySolver s;
  s.factor(good);
  SpMat singular = mesh_laplacian(gauss_test::icosphere(3), {}, 4);  // no pin: the constants are a null space
  EXPECT_THROW(s.factor(singular), std::runtime_error);
  SpMat indefinite = good;
  indefinite.coeffRef(100, 100) = -1.0;
  EXPECT_THROW(s.factor(indefinite), std::runtime_error);
  SpMat not_finite = good;
  not_finite.coeffRef(50, 50) = std::nan("");
  EXPECT_THROW(s.factor(not_finite), std::runtime_error);
  expect_matches_eigen(good, s, 1e-12);
}

TEST(CholeskySolver, ProgressRisesToOneThroughTheFactorPhases) {
  const SpMat A = mesh_laplacian(gauss_test::grid_cube(100), {0}, 2);
  gauss::Progress progress;
  std::atomic<bool> done{false};
  std::vector<double> seen;
  std::vector<std::string> phases;
  std::thread watcher([&] {
    while (!done) {
      seen.push_back(progress.fraction());
      if (phases.empty() || phases.back() != progress.phase()) phases.push_back(progress.phase());
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  // Joined however factor() ends: a throw (say, too little memory) must fail the test, not terminate it.
  struct JoinWatcher {
    std::atomic<bool>& done;
    std::thread& thread;
    ~JoinWatcher() {
      done = true;
      thread.join();
    }
  };
  {
    JoinWatcher join{done, watcher};
    gauss::CholeskySolver s;
    s.factor(A, &progress);
  }
  EXPECT_EQ(progress.fraction(), 1.0);
  EXPECT_STREQ(progress.phase(), "done");
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GT(progress.seconds(gauss::SetupPhase::factorizing), 0.0);
  EXPECT_EQ(progress.seconds(gauss::SetupPhase::topology), 0.0);  // not a phase of factor()
}

TEST(CholeskySolver, CancelStopsTheFactorizationPromptlyAndKeepsThePreviousFactor) {
  const SpMat small = random_spd(300, 3, 2);
  const SpMat large = mesh_laplacian(gauss_test::grid_cube(160), {0}, 3);  // 153,602 unknowns
  gauss::CholeskySolver s;
  s.factor(small);
  {
    gauss::Progress cancelled;
    cancelled.cancel();
    EXPECT_THROW(s.factor(large, &cancelled), gauss::Cancelled);
  }
  for (const char* phase : {"ordering", "symbolic", "factorizing"}) {
    gauss::Progress progress;
    std::atomic<double> cancelled_at{0.0};
    std::thread canceller([&] {
      // Cancel in `phase` (or, if this thread was too slow to see it, in a later one).
      const std::vector<std::string> order = {"ordering", "symbolic", "factorizing", "done"};
      auto rank = [&](const std::string& p) { return std::find(order.begin(), order.end(), p) - order.begin(); };
      while (rank(progress.phase()) < rank(phase)) std::this_thread::yield();
      cancelled_at = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
      progress.cancel();
    });
    double thrown_at = 0;
    try {
      s.factor(large, &progress);
    } catch (const gauss::Cancelled&) {
      thrown_at = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    }
    canceller.join();
    SCOPED_TRACE(phase);
    ASSERT_GT(thrown_at, 0.0) << "finished before the cancel took effect";
    EXPECT_LT(thrown_at - cancelled_at, 0.5);  // ~0.1 s on an idle machine; shared CI machines are slower
  }
  expect_matches_eigen(small, s, 1e-12);
}

}  // namespace test_cholesky_solver
