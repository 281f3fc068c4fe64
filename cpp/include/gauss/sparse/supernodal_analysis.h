#pragma once
// Symbolic analysis for a supernodal Cholesky factorization A = L L^T: everything about L that does
// not depend on A's values, computed once per pattern, so that the numeric factorization
// (supernodal_factor.h) only does dense arithmetic and the solve streams contiguous blocks.
//
// A supernode is a run of consecutive columns of L with (nearly) the same rows below them; its part
// of L is stored as one dense block. Supernodes are the fundamental ones (Liu, Ng & Peyton 1993),
// merged with their parent when the explicit zeros that adds stay few ("relaxed", as in CHOLMOD).
//
// Parallelism: the supernodal tree is cut, by estimated work, into kFactorParts groups of whole
// subtrees plus the supernodes above the cut (the top). Supernodes are numbered part by part, then
// the top, so each part is a contiguous range of columns and nothing in one part reads or writes
// another. The cut is always into kFactorParts whatever the number of threads: it decides the
// numbering and with it the rounding, and results must not depend on the thread count.
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "gauss/sparse/elimination_tree.h"
#include "gauss/util/progress.h"

namespace gauss {

constexpr int kFactorParts = 2;
// The numeric factorization computes an update's dense product in slices of this many columns (of
// the rows it updates), so its workspace stays small: max_update_columns * kUpdateSlice.
constexpr int kUpdateSlice = 256;

struct SupernodalStructure {
  int n = 0;
  std::vector<int> new_of_old;  // n: row of A -> row of L
  // Supernode s owns columns [col_start[s], col_start[s+1]) (its width w_s) and the rows
  // R_s = rows[row_start[s] .. row_start[s+1]) (m_s of them, ascending; the first w_s are its own
  // columns). Its block of L, transposed, is U_s = L(R_s, cols)^T: w_s by m_s, column-major, at
  // value_start[s] of the value array (so column c of U_s is row R_s[c] of L, contiguous).
  std::vector<int> col_start;        // #S + 1
  std::vector<int> row_start, rows;  // #S + 1, sum of m_s
  std::vector<int64_t> value_start;  // #S + 1
  std::vector<int> super_of_col;     // n
  // Parts: supernodes [part_start[p], part_start[p+1]) for p < kFactorParts; the top is
  // [part_start[kFactorParts], #S). Columns of the top start at top_col.
  std::vector<int> part_start;  // kFactorParts + 1
  int top_col = 0;
  // Updates. Within a part and within the top, left-looking: supernode s receives one from each
  // supernode d listed in update_source[update_start[s] .. update_start[s+1]) (ascending d). Rows
  // R_d[update_offset ..] are the rows of d at or below s's first column; the first update_count of
  // them are s's columns. From a part into the top, right-looking: once factored, supernode d of a
  // part sends its rows R_d[top_offset[d] ..] (those above the cut) to the top supernodes they
  // belong to (top_offset: one per part supernode; m_d if none).
  std::vector<int> update_start, update_source, update_offset, update_count;
  std::vector<int> top_offset;
  // Estimated floating-point work of each supernode (its updates and its dense factorization),
  // for progress reports.
  std::vector<double> work;
  // A with rows and columns numbered as L, lower triangle by columns, for assembling the blocks.
  LowerColumns A;
  // Most columns of a target any update touches (update_count, and the same for pushed updates),
  // for the numeric factorization's workspace.
  int max_update_columns = 0;

  int num_supernodes() const { return static_cast<int>(col_start.size()) - 1; }
  int64_t num_values() const { return value_start.empty() ? 0 : value_start.back(); }
  int64_t top_values() const;  // values of the top's blocks
  // Bytes the numeric factorization and the factor it produces will need on top of this structure.
  int64_t numeric_bytes() const;
};

// A_lower: the lower triangle of a symmetric n by n matrix (entries above the diagonal are ignored).
// old_of_new (n): a fill-reducing ordering of A (row old_of_new[k] of A eliminated k-th); the
// structure keeps its fill but renumbers within the elimination tree (postorder, parts).
// Reports SetupPhase::symbolic progress and throws Cancelled when cancelled.
SupernodalStructure analyse_supernodal(const Eigen::SparseMatrix<double>& A_lower,
                                       const std::vector<int>& old_of_new, Progress& progress);

}  // namespace gauss
