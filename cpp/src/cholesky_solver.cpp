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
  row_index_.clear();
  values_.clear();
  for (int j = 0; j < n_; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if (it.row() > j) {
        row_index_.push_back(static_cast<int>(it.row()));
        values_.push_back(it.value());
      }
    col_start_[j + 1] = static_cast<int>(values_.size());
  }
}

void CholeskySolver::solve_in_place(double* B, double* y) const {
  for (int i = 0; i < n_; ++i) {
    const int p = perm_[i];
    y[3 * i] = B[3 * p];
    y[3 * i + 1] = B[3 * p + 1];
    y[3 * i + 2] = B[3 * p + 2];
  }
  // L y = Pb, column-oriented (scatter into later rows).
  for (int j = 0; j < n_; ++j) {
    const double y0 = y[3 * j], y1 = y[3 * j + 1], y2 = y[3 * j + 2];
    for (int k = col_start_[j]; k < col_start_[j + 1]; ++k) {
      double* r = y + 3 * row_index_[k];
      const double l = values_[k];
      r[0] -= l * y0;
      r[1] -= l * y1;
      r[2] -= l * y2;
    }
  }
  for (int i = 0; i < n_; ++i) {
    y[3 * i] *= inv_diag_[i];
    y[3 * i + 1] *= inv_diag_[i];
    y[3 * i + 2] *= inv_diag_[i];
  }
  // L^T x = y, row-oriented over L's columns (gather from later rows).
  for (int j = n_ - 1; j >= 0; --j) {
    double s0 = y[3 * j], s1 = y[3 * j + 1], s2 = y[3 * j + 2];
    for (int k = col_start_[j]; k < col_start_[j + 1]; ++k) {
      const double* r = y + 3 * row_index_[k];
      const double l = values_[k];
      s0 -= l * r[0];
      s1 -= l * r[1];
      s2 -= l * r[2];
    }
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
