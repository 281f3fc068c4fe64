#include "gauss/cholesky_solver.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>

namespace gauss {

void CholeskySolver::factor(const Eigen::SparseMatrix<double>& A) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  ldlt.compute(A);
  if (ldlt.info() != Eigen::Success)
    throw std::runtime_error("the mesh's Laplacian could not be factored (the mesh is too degenerate)");
  const Eigen::VectorXd D = ldlt.vectorD();
  n_ = static_cast<int>(A.rows());
  inv_diag_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    if (!(D[i] > 0) || !std::isfinite(D[i]))
      throw std::runtime_error("the mesh's Laplacian is not positive definite (degenerate geometry)");
    inv_diag_[i] = 1.0 / D[i];
  }
  // P A P^T = L D L^T with (P b)[indices[i]] = b[i]; we store the inverse map for a gather.
  perm_.resize(n_);
  const auto& idx = ldlt.permutationP().indices();
  for (int i = 0; i < n_; ++i) perm_[idx[i]] = i;

  Eigen::SparseMatrix<double> L = ldlt.matrixL();
  L.makeCompressed();
  col_start_.assign(n_ + 1, 0);
  col_rows_.clear();
  col_values_.clear();
  row_start_.assign(n_ + 1, 0);
  for (int j = 0; j < n_; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if (it.row() > j) {
        col_rows_.push_back(static_cast<int>(it.row()));
        col_values_.push_back(it.value());
        ++row_start_[it.row() + 1];
      }
    col_start_[j + 1] = static_cast<int>(col_values_.size());
  }
  for (int i = 0; i < n_; ++i) row_start_[i + 1] += row_start_[i];
  row_cols_.resize(col_rows_.size());
  row_values_.resize(col_values_.size());
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  for (int j = 0; j < n_; ++j)  // columns in increasing order: each row's entries come out sorted
    for (int k = col_start_[j]; k < col_start_[j + 1]; ++k) {
      const int slot = fill[col_rows_[k]]++;
      row_cols_[slot] = j;
      row_values_[slot] = col_values_[k];
    }
}

namespace {

// s -= sum_k values[k] * y[idx[k]] for the three columns. Two independent accumulator sets halve the
// floating-point dependency chain that otherwise bounds these sweeps; the pairing is fixed, so the
// result does not depend on anything but the data.
inline void subtract_gather(const int* idx, const double* values, int begin, int end, const double* y,
                            double& s0, double& s1, double& s2) {
  double a0 = 0, a1 = 0, a2 = 0, b0 = 0, b1 = 0, b2 = 0;
  int k = begin;
  for (; k + 1 < end; k += 2) {
    const double* r = y + 3 * idx[k];
    const double* t = y + 3 * idx[k + 1];
    const double l = values[k], m = values[k + 1];
    a0 += l * r[0];
    a1 += l * r[1];
    a2 += l * r[2];
    b0 += m * t[0];
    b1 += m * t[1];
    b2 += m * t[2];
  }
  if (k < end) {
    const double* r = y + 3 * idx[k];
    const double l = values[k];
    a0 += l * r[0];
    a1 += l * r[1];
    a2 += l * r[2];
  }
  s0 -= a0 + b0;
  s1 -= a1 + b1;
  s2 -= a2 + b2;
}

}  // namespace

void CholeskySolver::solve_in_place(double* B, double* y) const {
  // Forward: L y = P b, row by row.
  for (int i = 0; i < n_; ++i) {
    const int p = perm_[i];
    double s0 = B[3 * p], s1 = B[3 * p + 1], s2 = B[3 * p + 2];
    subtract_gather(row_cols_.data(), row_values_.data(), row_start_[i], row_start_[i + 1], y, s0, s1, s2);
    y[3 * i] = s0;
    y[3 * i + 1] = s1;
    y[3 * i + 2] = s2;
  }
  for (int i = 0; i < n_; ++i) {
    y[3 * i] *= inv_diag_[i];
    y[3 * i + 1] *= inv_diag_[i];
    y[3 * i + 2] *= inv_diag_[i];
  }
  // Backward: L^T x = y, column by column of L.
  for (int j = n_ - 1; j >= 0; --j) {
    double s0 = y[3 * j], s1 = y[3 * j + 1], s2 = y[3 * j + 2];
    subtract_gather(col_rows_.data(), col_values_.data(), col_start_[j], col_start_[j + 1], y, s0, s1, s2);
    y[3 * j] = s0;
    y[3 * j + 1] = s1;
    y[3 * j + 2] = s2;
  }
  for (int i = 0; i < n_; ++i) {
    const int p = perm_[i];
    B[3 * p] = y[3 * i];
    B[3 * p + 1] = y[3 * i + 1];
    B[3 * p + 2] = y[3 * i + 2];
  }
}

}  // namespace gauss
