// The supernodal factorization's dense kernel (dense_block.h) against Eigen's dense LLT: the factored
// block, the rows beside it, the same bits with and without the thread pool, and its refusals.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "gauss/sparse/dense_block.h"
#include "gauss/util/parallel.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_dense_block {

namespace {

using Dense = Eigen::MatrixXd;

// A w by m block as factor_block takes it: [A11 A12] with A11 SPD (only its upper triangle is
// meaningful; the strict lower triangle holds garbage the kernel must ignore).
Dense random_block(int w, int m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Dense B(w, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < w; ++i) B(i, j) = value(rng);
  Dense G = B.leftCols(w);
  B.leftCols(w) = G * G.transpose() + w * Dense::Identity(w, w);
  for (int j = 0; j < w; ++j)
    for (int i = j + 1; i < w; ++i) B(i, j) = 1e30;  // below the diagonal: never read
  return B;
}

Dense upper_symmetric(const Dense& A11) { return Dense(A11.selfadjointView<Eigen::Upper>()); }

}  // namespace

TEST(DenseBlock, FactorsTheDiagonalBlockAndSolvesTheRowsBeside) {
  gauss::Progress progress;
  // Widths below, at and above the tile (128), with and without rows beside.
  for (int w : {1, 2, 17, 128, 129, 300})
    for (int beside : {0, 1, 40, 260}) {
      const int m = w + beside;
      SCOPED_TRACE("w " + std::to_string(w) + ", m " + std::to_string(m));
      const Dense B = random_block(w, m, 100u * w + beside);
      Dense U = B;
      ASSERT_TRUE(gauss::factor_block(U.data(), w, m, false, progress));
      const Dense A11 = upper_symmetric(B.leftCols(w));
      const Eigen::LLT<Dense> llt(A11);
      ASSERT_EQ(llt.info(), Eigen::Success);
      const Dense U11 = U.leftCols(w).triangularView<Eigen::Upper>();
      const double scale = A11.cwiseAbs().maxCoeff();
      EXPECT_LT((U11.transpose() * U11 - A11).cwiseAbs().maxCoeff(), 1e-13 * scale * w);
      EXPECT_LT((U11 - Dense(llt.matrixU())).cwiseAbs().maxCoeff(), 1e-12 * std::sqrt(scale) * w);
      EXPECT_GT(U11.diagonal().minCoeff(), 0.0);
      if (beside > 0) {
        // U11^T U12 = A12.
        const Dense A12 = B.rightCols(beside);
        EXPECT_LT((U11.transpose() * U.rightCols(beside) - A12).cwiseAbs().maxCoeff(), 1e-12 * w);
      }
    }
}

TEST(DenseBlock, SameBitsWithAndWithoutThreads) {
  gauss::Progress progress;
  gauss::parallel::ScopedThreads threads(4);
  for (int w : {130, 400}) {
    const Dense B = random_block(w, w + 300, 7u + w);
    Dense serial = B, parallel = B;
    ASSERT_TRUE(gauss::factor_block(serial.data(), w, w + 300, false, progress));
    ASSERT_TRUE(gauss::factor_block(parallel.data(), w, w + 300, true, progress));
    EXPECT_EQ(std::memcmp(serial.data(), parallel.data(), sizeof(double) * serial.size()), 0) << "w " << w;
  }
}

TEST(DenseBlock, RefusesIndefiniteNonFiniteAndCancelled) {
  gauss::Progress progress;
  for (int w : {3, 200}) {
    SCOPED_TRACE("w " + std::to_string(w));
    Dense indefinite = random_block(w, w + 5, 1);
    indefinite(w - 1, w - 1) = -1.0;  // the last pivot goes negative
    EXPECT_FALSE(gauss::factor_block(indefinite.data(), w, w + 5, false, progress));
    Dense nan = random_block(w, w + 5, 2);
    nan(0, w / 2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(gauss::factor_block(nan.data(), w, w + 5, false, progress));
  }
  // Cancellation is checked between tile steps, so it shows on blocks wider than one tile.
  gauss::Progress cancelled;
  cancelled.cancel();
  Dense B = random_block(300, 300, 3);
  EXPECT_FALSE(gauss::factor_block(B.data(), 300, 300, false, cancelled));
}

}  // namespace test_dense_block
