#include "gauss/solver/normal_step.h"

#include <Eigen/Geometry>  // cross
#include <algorithm>
#include <cmath>

#include "gauss/settings.h"

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

// The blend's g, gradient and Hessian: each style's, scaled by its share.
void evaluate_blend(const PreferenceFunction* styles, const StyleShare* shares, int count, const Vector3d& n,
                    const Vector3d* preferred, double& g, Vector3d& grad, Matrix3d& hess) {
  g = 0;
  grad.setZero();
  hess.setZero();
  for (int k = 0; k < count; ++k) {
    double gk;
    Vector3d grad_k;
    Matrix3d hess_k;
    evaluate_style(styles[shares[k].style], n, preferred, gk, grad_k, hess_k);
    g += shares[k].share * gk;
    grad += shares[k].share * grad_k;
    hess += shares[k].share * hess_k;
  }
}

}  // namespace

namespace {

// trust_region_normal(): tries per call, the radius quartered after each step that the objective does
// not confirm (its decrease below a tenth of the model's).
constexpr int kTrustRegionTries = 4;

// The 2 by 2 trust-region subproblem min g.s + s.H s / 2 over |s| <= radius (H symmetric), solved
// exactly: H's eigenvectors, then the shift mu >= max(0, -smallest eigenvalue) that puts the step on the
// boundary (the "hard case", g orthogonal to the lowest eigenvector, filled up along it).
Eigen::Vector2d trust_region_step(const Eigen::Matrix2d& H, const Eigen::Vector2d& g, double radius) {
  const double a = H(0, 0), b = H(0, 1), c = H(1, 1);
  const double mean = 0.5 * (a + c), half = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double l1 = mean - half, l2 = mean + half;
  Eigen::Vector2d q1 = std::abs(b) > 1e-300 ? Eigen::Vector2d(b, l1 - a)
                                            : (a <= c ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1));
  q1.normalize();
  const Eigen::Vector2d q2(-q1.y(), q1.x());
  const double a1 = q1.dot(g), a2 = q2.dot(g);
  // Not std::hypot: glibc 2.35 versioned it anew, and the module must load on glibc 2.28
  // (cpp/python/glibc_baseline.cpp); an overflow to infinity only reads as "longer than the radius".
  auto length = [&](double mu) {
    const double x = a1 / (l1 + mu), y = a2 / (l2 + mu);
    return std::sqrt(x * x + y * y);
  };
  if (l1 > 0 && length(0) <= radius) return -(a1 / l1) * q1 - (a2 / l2) * q2;
  const double lo = std::max(0.0, -l1);
  const double tiny = 1e-12 * (std::abs(l1) + std::abs(l2) + g.norm() + 1e-300);
  if (length(lo + tiny) <= radius) {  // the hard case: fill up along q1
    const Eigen::Vector2d s = -(a2 / (l2 + lo + tiny)) * q2;
    const double rest = std::sqrt(std::max(0.0, radius * radius - s.squaredNorm()));
    return s + (a1 > 0 ? -rest : rest) * q1;
  }
  // Newton on phi(mu) = 1 / |s(mu)| - 1 / radius, concave and increasing for mu > lo: from the left
  // its iterates rise monotonically to the root (Moré and Sorensen), in a handful of steps here.
  double mu = lo + tiny;
  for (int i = 0; i < 50; ++i) {
    const double x1 = a1 / (l1 + mu), x2 = a2 / (l2 + mu), norm = std::sqrt(x1 * x1 + x2 * x2);
    const double phi = 1 / norm - 1 / radius;
    if (!(std::abs(phi) > 1e-12 / radius)) break;
    const double slope = (x1 * x1 / (l1 + mu) + x2 * x2 / (l2 + mu)) / (norm * norm * norm);
    const double next = mu - phi / slope;
    if (!(next > mu)) break;  // at the root to rounding (or not finite)
    mu = next;
  }
  return -(a1 / (l1 + mu)) * q1 - (a2 / (l2 + mu)) * q2;
}

// One trust-region Newton step on the sphere for Eq. 18's
// L_n(n) = -g(n) + sum_k lw_k / 2 (u_k + n . es_k)^2: the Riemannian gradient P grad and Hessian
// P Hess P - (n . grad) P in a tangent basis, the step retracted by normalizing. The radius starts at
// 1 / sqrt(sigma), the width of one bump of g, so a step cannot cross to another preferred normal's
// bump; a step the objective does not confirm is retried at a quarter of the radius, and after
// kTrustRegionTries n stays.
template <class Evaluate>
Vector3d trust_region_update(const Evaluate& evaluate, const Vector3d& n, const Vector3d* es, const double* lw,
                             const double* u, double sigma) {
  auto objective = [&](const Vector3d& x, Vector3d* G, Matrix3d* Hs) {
    double g;
    Vector3d grad_g;
    Matrix3d hess_g;
    evaluate(x, g, grad_g, hess_g);
    double f = -g;
    if (G) *G = -grad_g;
    if (Hs) *Hs = -hess_g;
    for (int k = 0; k < 3; ++k) {
      const double r = u[k] + x.dot(es[k]);
      f += 0.5 * lw[k] * r * r;
      if (G) *G += (lw[k] * r) * es[k];
      if (Hs) Hs->noalias() += lw[k] * (es[k] * es[k].transpose());
    }
    return f;
  };
  Vector3d G;
  Matrix3d Hs;
  const double f = objective(n, &G, &Hs);
  Vector3d t1 = std::abs(n.x()) < 0.6 ? Vector3d::UnitX()
                                      : (std::abs(n.y()) < 0.6 ? Vector3d::UnitY() : Vector3d::UnitZ());
  t1 = (t1 - t1.dot(n) * n).normalized();
  const Vector3d t2 = n.cross(t1);
  const Eigen::Vector2d gr(t1.dot(G), t2.dot(G));
  if (!(gr.norm() > 1e-14)) return n;  // stationary (or not finite)
  const double radial = n.dot(G);
  Eigen::Matrix2d Hr;
  Hr << t1.dot(Hs * t1) - radial, t1.dot(Hs * t2), t2.dot(Hs * t1), t2.dot(Hs * t2) - radial;
  double radius = 1 / std::sqrt(sigma);
  for (int attempt = 0; attempt < kTrustRegionTries; ++attempt, radius *= 0.25) {
    const Eigen::Vector2d s = trust_region_step(Hr, gr, radius);
    const double predicted = gr.dot(s) + 0.5 * s.dot(Hr * s);
    if (!(predicted < 0) || !s.allFinite()) break;
    const Vector3d m = (n + s.x() * t1 + s.y() * t2).normalized();
    if ((objective(m, nullptr, nullptr) - f) / predicted > 0.1) return m;
  }
  return n;
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
  double g;
  Vector3d grad_sum;
  Matrix3d hess_sum;
  evaluate_blend(styles, shares, count, n, preferred, g, grad_sum, hess_sum);
  return newton_update(grad_sum, hess_sum, n, es, lw, u);
}

bool takes_trust_region_step(const PreferenceFunction& style) {
  return style.sigma() > settings::paper_step_max_sigma && style.kind() == StyleKind::directions &&
         !style.has_rings() && style.separation() > settings::trust_region_min_separation;
}

Vector3d trust_region_normal(const PreferenceFunction& style, const Vector3d& n, const Vector3d* es, const double* lw,
                             const double* u, const Vector3d* preferred) {
  auto evaluate = [&](const Vector3d& x, double& g, Vector3d& grad, Matrix3d& hess) {
    evaluate_style(style, x, preferred, g, grad, hess);
  };
  return trust_region_update(evaluate, n, es, lw, u, style.sigma());
}

Vector3d trust_region_normal(const PreferenceFunction* styles, const StyleShare* shares, int count, const Vector3d& n,
                             const Vector3d* es, const double* lw, const double* u, const Vector3d* preferred) {
  double sigma = 0;
  for (int k = 0; k < count; ++k) sigma = std::max(sigma, styles[shares[k].style].sigma());
  auto evaluate = [&](const Vector3d& x, double& g, Vector3d& grad, Matrix3d& hess) {
    evaluate_blend(styles, shares, count, x, preferred, g, grad, hess);
  };
  return trust_region_update(evaluate, n, es, lw, u, sigma);
}

}  // namespace gauss
