#include "gauss/preference_function.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gauss {
namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Solves K w = 1 for a symmetric kernel matrix K. K can be singular when the user repeats a normal;
// the minimum-norm solution then splits the weight between the copies, which keeps g(n_k) = 1.
std::vector<double> solve_unit_weights(const Eigen::MatrixXd& K, const char* what) {
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(K.rows());
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(K);
  const Eigen::VectorXd w = cod.solve(ones);
  if (!w.allFinite() || (K * w - ones).cwiseAbs().maxCoeff() > 1e-6) {
    std::ostringstream msg;
    msg << "could not normalize the style's " << what
        << " so that g = 1 at each of them; try a larger sigma or fewer, more distinct directions";
    throw std::invalid_argument(msg.str());
  }
  return std::vector<double>(w.data(), w.data() + w.size());
}

}  // namespace

PreferenceFunction::PreferenceFunction(const StyleParams& p) : sigma_(p.sigma), mu_(p.mu) {
  if (!std::isfinite(p.sigma) || p.sigma <= 0)
    throw std::invalid_argument("sigma must be a finite number > 0");
  if (!std::isfinite(p.mu) || p.mu < 0) throw std::invalid_argument("mu must be a finite number >= 0");
  if (!std::isfinite(p.axis_contribution) || p.axis_contribution < 0)
    throw std::invalid_argument("axis_contribution must be a finite number >= 0");
  if (!p.rotation.allFinite() ||
      (p.rotation.transpose() * p.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      p.rotation.determinant() < 0)
    throw std::invalid_argument("rotation must be a 3x3 rotation matrix (orthonormal, determinant +1)");
  if (p.normals.empty() && p.ring_offsets.empty())
    throw std::invalid_argument("a style needs at least one preferred normal or one ring");

  for (const Eigen::Vector3d& n : p.normals) {
    const double len = n.norm();
    if (!finite(n) || !(len > 1e-12))
      throw std::invalid_argument("preferred normals must be finite, non-zero 3-vectors");
    normals_.push_back(p.rotation * (n / len));
  }
  if (!p.ring_offsets.empty()) {
    const double len = p.axis.norm();
    if (!finite(p.axis) || !(len > 1e-12))
      throw std::invalid_argument("the ring axis must be a finite, non-zero 3-vector");
    for (double d : p.ring_offsets)
      if (!std::isfinite(d) || std::abs(d) >= 1.0)
        throw std::invalid_argument("ring offsets must lie strictly between -1 and 1");
    offsets_ = p.ring_offsets;
  }
  axis_ = p.rotation * (p.axis.norm() > 1e-12 ? Eigen::Vector3d(p.axis.normalized())
                                              : Eigen::Vector3d::UnitZ());

  const int K = static_cast<int>(normals_.size());
  if (K > 0) {
    Eigen::MatrixXd A(K, K);
    for (int i = 0; i < K; ++i)
      for (int j = 0; j < K; ++j) A(i, j) = std::exp(sigma_ * (normals_[i].dot(normals_[j]) - 1.0));
    normal_weights_ = solve_unit_weights(A, "preferred normals");
    if (has_rings())
      for (double& w : normal_weights_) w *= p.axis_contribution;
  }
  const int R = static_cast<int>(offsets_.size());
  if (R > 0) {
    Eigen::MatrixXd B(R, R);
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < R; ++j) {
        const double t = offsets_[i] - offsets_[j];
        B(i, j) = std::exp(-sigma_ * t * t);
      }
    ring_weights_ = solve_unit_weights(B, "rings");
  }
}

double PreferenceFunction::value(const Eigen::Vector3d& x) const {
  double g = 0.0;
  for (size_t k = 0; k < normals_.size(); ++k)
    g += normal_weights_[k] * std::exp(sigma_ * (x.dot(normals_[k]) - 1.0));
  if (has_rings()) {
    const double ax = x.dot(axis_);
    for (size_t r = 0; r < offsets_.size(); ++r) {
      const double t = ax - offsets_[r];
      g += ring_weights_[r] * std::exp(-sigma_ * t * t);
    }
  }
  return g;
}

void PreferenceFunction::evaluate(const Eigen::Vector3d& x, double& g, Eigen::Vector3d& grad,
                                  Eigen::Matrix3d& hess) const {
  g = 0.0;
  grad.setZero();
  hess.setZero();
  const double s = sigma_;
  for (size_t k = 0; k < normals_.size(); ++k) {
    const Eigen::Vector3d& n = normals_[k];
    const double e = normal_weights_[k] * std::exp(s * (x.dot(n) - 1.0));
    g += e;
    grad += (s * e) * n;
    hess.noalias() += (s * s * e) * (n * n.transpose());
  }
  if (has_rings()) {
    const double ax = x.dot(axis_);
    double dg = 0.0, ddg = 0.0;  // derivatives of the ring terms along the axis
    for (size_t r = 0; r < offsets_.size(); ++r) {
      const double t = ax - offsets_[r];
      const double c = ring_weights_[r] * std::exp(-s * t * t);
      g += c;
      dg += -2.0 * s * t * c;
      ddg += 2.0 * s * (2.0 * s * t * t - 1.0) * c;
    }
    grad += dg * axis_;
    hess.noalias() += ddg * (axis_ * axis_.transpose());
  }
}

}  // namespace gauss
