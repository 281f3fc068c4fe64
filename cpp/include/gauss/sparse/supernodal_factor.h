#pragma once
// Numeric supernodal Cholesky factorization A = L L^T, left-looking, on the structure computed by
// supernodal_analysis.h, with Eigen's dense kernels for the blocks (no BLAS library needed).
//
// Supernode by supernode: A's columns are assembled into the block, every descendant that reaches
// it subtracts its update (one dense product each, in ascending order of the descendant), then the
// block's diagonal is factored (dense Cholesky) and the rows below it solved for. The parts of the
// structure run in parallel (nothing in one part touches another), the top after them.
//
// Input:  S, the structure (S.A holds A's values).
// Output: S.num_values() doubles, allocated here: the block U_s of every supernode (layout in
//         supernodal_analysis.h); U_s's diagonal block is upper triangular with a positive diagonal.
// Throws std::runtime_error if A is not numerically positive definite, Cancelled when the progress
// is cancelled (SetupPhase::factorizing), OutOfMemory if the blocks cannot be allocated.
// Bit-identical for any number of threads: every supernode is computed by the same operations, on
// one thread, in an order fixed by the structure.
#include <cstdlib>
#include <memory>

#include "gauss/util/progress.h"
#include "gauss/sparse/supernodal_analysis.h"

namespace gauss {

// The factor's values come from std::malloc, so that they can be shrunk in place (std::realloc):
// CholeskySolver rounds them to floats within the same block.
struct FreeDeleter {
  void operator()(void* p) const { std::free(p); }
};
using FactorValues = std::unique_ptr<double[], FreeDeleter>;

FactorValues factor_supernodal(const SupernodalStructure& S, Progress& progress);

}  // namespace gauss
