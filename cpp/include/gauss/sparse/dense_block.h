#pragma once
// Dense kernel of the supernodal Cholesky factorization (supernodal_factor.cpp), on Eigen.
//
// A supernode's block is U = L(rows, cols)^T: w by m, column-major with leading dimension w; its first
// w columns are the (upper triangular) diagonal block, the other m - w columns the rows of L below it.
#include "gauss/util/progress.h"

namespace gauss {

// Factors a block in place. On entry U holds the upper triangle of the diagonal block of the
// (updated) matrix and the w by (m - w) block beside it; on exit U11 with U11^T U11 = A11 (positive
// diagonal) and U12 = U11^-T A12.
// Blocks wider than one tile are factored tile by tile (right-looking); with `parallel` the tiles of
// each step run on the thread pool. The tiling depends only on w and m, so the result does not
// depend on the number of threads.
// Returns false if the diagonal block is not positive definite or not finite, and also when the
// progress was cancelled (checked between tile steps; the caller tells the two apart).
bool factor_block(double* U, int w, int m, bool parallel, const Progress& progress);

}  // namespace gauss
