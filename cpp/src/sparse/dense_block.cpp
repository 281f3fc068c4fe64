#include "gauss/sparse/dense_block.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "gauss/util/parallel.h"

namespace gauss {
namespace {

// Columns per tile: large enough for Eigen's kernels to run at speed, small enough that the
// largest separators of a big mesh split into enough tiles for two threads (their size:
// docs/performance.md#set-up-at-scale).
constexpr int kTile = 128;

using Strided = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

}  // namespace

bool factor_block(double* U, int w, int m, bool parallel, const Progress& progress) {
  auto block = [&](int row, int col, int rows, int cols) {
    return Strided(U + row + static_cast<int64_t>(w) * col, rows, cols, Eigen::OuterStride<>(w));
  };
  for (int k0 = 0; k0 < w; k0 += kTile) {
    if (progress.cancelled()) return false;
    const int k1 = std::min(k0 + kTile, w), b = k1 - k0;
    // The diagonal tile.
    Strided diagonal = block(k0, k0, b, b);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>, Eigen::Upper> llt(diagonal);
    if (llt.info() != Eigen::Success) return false;
    for (int k = 0; k < b; ++k) {
      const double d = diagonal(k, k);
      if (!(d > 0) || !std::isfinite(d)) return false;
    }
    // Its rows right of it: U[k0:k1, k1:m] = U[k0:k1, k0:k1]^-T U[k0:k1, k1:m], tile by tile.
    const int tiles = (m - k1 + kTile - 1) / kTile;
    parallel::for_tasks(tiles, parallel, [&](int t) {
      const int j0 = k1 + t * kTile, j1 = std::min(j0 + kTile, m);
      Strided right = block(k0, j0, b, j1 - j0);
      diagonal.triangularView<Eigen::Upper>().transpose().solveInPlace(right);
    });
    // The rest of the diagonal block and the rows beside it: U[k1:w, j] -= U[k0:k1, k1:w]^T U[k0:k1, j]
    // (only rows up to the column in the diagonal block, where the lower part is not used).
    parallel::for_tasks(tiles, parallel, [&](int t) {
      const int j0 = k1 + t * kTile, j1 = std::min(j0 + kTile, m);
      const int rows = std::min(w, j1) - k1;
      if (rows <= 0) return;
      block(k1, j0, rows, j1 - j0).noalias() -= block(k0, k1, b, rows).transpose() * block(k0, j0, b, j1 - j0);
    });
  }
  return true;
}

}  // namespace gauss
