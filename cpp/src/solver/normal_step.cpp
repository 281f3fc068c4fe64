#include "gauss/solver/normal_step.h"

#include <cmath>

namespace gauss {

using Eigen::Matrix3d;
using Eigen::Vector3d;

bool solve_symmetric3(const Matrix3d& H, const Vector3d& b, Vector3d& x) {
  const double c00 = H(1, 1) * H(2, 2) - H(1, 2) * H(2, 1);
  const double c01 = H(1, 2) * H(2, 0) - H(1, 0) * H(2, 2);
  const double c02 = H(1, 0) * H(2, 1) - H(1, 1) * H(2, 0);
  const double det = H(0, 0) * c00 + H(0, 1) * c01 + H(0, 2) * c02;
  const double scale = H.cwiseAbs().maxCoeff();
  if (!(std::abs(det) > 1e-12 * scale * scale * scale) || !std::isfinite(det)) return false;
  Matrix3d adj;
  adj << c00, H(0, 2) * H(2, 1) - H(0, 1) * H(2, 2), H(0, 1) * H(1, 2) - H(0, 2) * H(1, 1),
      c01, H(0, 0) * H(2, 2) - H(0, 2) * H(2, 0), H(0, 2) * H(1, 0) - H(0, 0) * H(1, 2),
      c02, H(0, 1) * H(2, 0) - H(0, 0) * H(2, 1), H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0);
  x = adj * b / det;
  return x.allFinite();
}

namespace {

// The Newton update of newton_normal() from g's gradient and Hessian at n.
Vector3d newton_update(const Vector3d& grad_g, const Matrix3d& hess_g, const Vector3d& n, const Vector3d* es,
                       const double* lw, const double* u) {
  Matrix3d H = -hess_g;
  Vector3d grad = -grad_g;
  for (int k = 0; k < 3; ++k) {
    H.noalias() += lw[k] * (es[k] * es[k].transpose());
    grad += (lw[k] * (es[k].dot(n) + u[k])) * es[k];
  }
  Vector3d newton;
  Vector3d d = Vector3d::Constant(NAN);  // stays NaN (-> the fallback below) if Newton fails
  if (solve_symmetric3(H, -grad, newton)) {
    d = newton - newton.dot(n) * n;
    // A tangential part at rounding level means Newton only rescales n (exactly so in the first
    // round for styles that depend on x.axis alone: plane, cylinder, cone); its sign is noise, and
    // trusting it made the result depend on the mesh's position. Use the fallback instead.
    if (!(d.squaredNorm() > 1e-16 * newton.squaredNorm())) d = Vector3d::Constant(NAN);
  }
  // Fall back to a projected gradient step when Newton fails or points uphill.
  if (!(d.allFinite() && d.dot(grad) <= 0)) d = -0.1 * (grad - grad.dot(n) * n);
  const Vector3d m = n + d;
  const double len = m.norm();
  return (len > 1e-300 && std::isfinite(len)) ? Vector3d(m / len) : n;
}

}  // namespace

namespace {

void evaluate_style(const PreferenceFunction& style, const Vector3d& n, const Vector3d* preferred, double& g,
                    Vector3d& grad_g, Matrix3d& hess_g) {
  if (preferred) style.evaluate(n, *preferred, g, grad_g, hess_g);
  else style.evaluate(n, g, grad_g, hess_g);
}

}  // namespace

Vector3d newton_normal(const PreferenceFunction& style, const Vector3d& n, const Vector3d* es, const double* lw,
                       const double* u, const Vector3d* preferred) {
  double g;
  Vector3d grad_g;
  Matrix3d hess_g;
  evaluate_style(style, n, preferred, g, grad_g, hess_g);
  return newton_update(grad_g, hess_g, n, es, lw, u);
}

Vector3d newton_normal(const PreferenceFunction* styles, const StyleShare* shares, int count, const Vector3d& n,
                       const Vector3d* es, const double* lw, const double* u, const Vector3d* preferred) {
  Vector3d grad_sum = Vector3d::Zero();
  Matrix3d hess_sum = Matrix3d::Zero();
  for (int k = 0; k < count; ++k) {
    double g;
    Vector3d grad_g;
    Matrix3d hess_g;
    evaluate_style(styles[shares[k].style], n, preferred, g, grad_g, hess_g);
    grad_sum += shares[k].share * grad_g;
    hess_sum += shares[k].share * hess_g;
  }
  return newton_update(grad_sum, hess_sum, n, es, lw, u);
}

}  // namespace gauss
