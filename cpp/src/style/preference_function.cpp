#include "gauss/style/preference_function.h"


#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gauss {
namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Solves K w = 1 for a symmetric kernel matrix K. K can be singular when the user repeats a normal;
// the minimum-norm solution then splits the weight between the copies, which keeps g(n_k) = 1.
// Eq. 10's weights: K w = 1. False if they cannot be found to 1e-6.
bool try_unit_weights(const Eigen::MatrixXd& K, std::vector<double>& weights) {
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(K.rows());
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(K);
  const Eigen::VectorXd w = cod.solve(ones);
  if (!w.allFinite() || (K * w - ones).cwiseAbs().maxCoeff() > 1e-6) return false;
  weights.assign(w.data(), w.data() + w.size());
  return true;
}

std::vector<double> solve_unit_weights(const Eigen::MatrixXd& K, const char* what) {
  std::vector<double> w;
  if (!try_unit_weights(K, w)) {
    std::ostringstream msg;
    msg << "could not normalize the style's " << what
        << " so that g = 1 at each of them; try a larger sigma or fewer, more distinct directions";
    throw std::invalid_argument(msg.str());
  }
  return w;
}

Eigen::MatrixXd bump_matrix(const std::vector<Eigen::Vector3d>& normals, double sigma) {
  const int K = static_cast<int>(normals.size());
  Eigen::MatrixXd A(K, K);
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < K; ++j) A(i, j) = std::exp(sigma * (normals[i].dot(normals[j]) - 1.0));
  return A;
}

}  // namespace

PreferenceFunction::PreferenceFunction(const StyleParams& p)
    : sigma_(p.sigma), mu_(p.mu), rotation_(p.rotation), kind_(p.kind) {
  settings::sigma.check(p.sigma);
  settings::mu.check(p.mu);
  settings::axis_contribution.check(p.axis_contribution);
  if (!p.rotation.allFinite() ||
      (p.rotation.transpose() * p.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      p.rotation.determinant() < 0)
    throw std::invalid_argument("rotation must be a 3x3 rotation matrix (orthonormal, determinant +1)");
  if (kind_ == StyleKind::developable) {
    if (!p.normals.empty() || !p.ring_offsets.empty())
      throw std::invalid_argument("a developable (sheet metal) style takes no preferred normals or rings: each "
                                  "face's preferred normal comes from its neighbourhood");
    axis_ = p.rotation * Eigen::Vector3d::UnitZ();
    return;
  }
  if (kind_ == StyleKind::gauss_map) {
    if (!p.ring_offsets.empty()) throw std::invalid_argument("an example's Gauss map style takes no rings");
    if (p.normals.empty()) throw std::invalid_argument("an example's Gauss map style needs at least one normal");
  } else if (!p.areas.empty()) {
    throw std::invalid_argument("only an example's Gauss map style takes areas");
  }
  if (p.normals.empty() && p.ring_offsets.empty())
    throw std::invalid_argument("a style needs at least one preferred normal or one ring");
  if (p.normals.size() > static_cast<size_t>(settings::max_style_normals)) {
    std::ostringstream msg;
    msg << "a style takes at most " << settings::max_style_normals << " preferred normals (got " << p.normals.size()
        << "); merge near-parallel ones first (gauss_core.merge_directions)";
    throw std::invalid_argument(msg.str());
  }
  if (p.ring_offsets.size() > static_cast<size_t>(settings::max_style_rings)) {
    std::ostringstream msg;
    msg << "a style takes at most " << settings::max_style_rings << " rings (got " << p.ring_offsets.size() << ")";
    throw std::invalid_argument(msg.str());
  }

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
  if (kind_ == StyleKind::gauss_map) {
    example_ = std::make_shared<const ExampleNormals>(normals_, p.areas);
    // All the bumps are summed only where Eq. 10 gives every one a positive weight, so that g peaks at
    // each direction (a cube, an icosahedron); crowded directions get weights of both signs and a g
    // that pulls towards none of them, so there each face snaps to its nearest (docs/styles.md#gauss-map).
    if (K > kExactNormals || !try_unit_weights(bump_matrix(normals_, sigma_), normal_weights_) ||
        *std::min_element(normal_weights_.begin(), normal_weights_.end()) <= 0) {
      normal_weights_.clear();
      return;
    }
  }

  if (K > kExactNormals) {
    field_ = std::make_shared<const NormalField>(normals_, sigma_, has_rings() ? p.axis_contribution : 1.0);
  } else if (K > 0) {
    if (!example_) normal_weights_ = solve_unit_weights(bump_matrix(normals_, sigma_), "preferred normals");
    if (example_)  // a small example's Gauss map: every direction, weighted by its pull
      for (int k = 0; k < K; ++k) normal_weights_[k] *= example_->pull()[k];
    if (has_rings())
      for (double& w : normal_weights_) w *= p.axis_contribution;
    // Terms in evaluation order: antipodal pairs (n, -n) first, each pair at an even position
    // with its second term marked, so that its exponential follows from the first's:
    // exp(s(-x.n - 1)) = exp(-2s) / exp(s(x.n - 1)). Then the unpaired normals.
    std::vector<int> order, singles;  // codes: k, or ~k for "second of a pair"
    std::vector<char> used(K, 0);
    for (int k = 0; k < K; ++k) {
      if (used[k]) continue;
      used[k] = 1;
      int partner = -1;
      for (int j = k + 1; j < K && partner < 0; ++j)
        if (!used[j] && (normals_[k] + normals_[j]).norm() < 1e-12) partner = j;
      if (partner < 0) {
        singles.push_back(k);
      } else {
        used[partner] = 1;
        order.push_back(k);
        order.push_back(~partner);
      }
    }
    order.insert(order.end(), singles.begin(), singles.end());
    for (int code : order) {
      const int k = code < 0 ? ~code : code;
      const Eigen::Vector3d& n = normals_[k];
      terms_.push_back({n.x(), n.y(), n.z(), n.x() * n.x(), n.x() * n.y(), n.x() * n.z(), n.y() * n.y(),
                        n.y() * n.z(), n.z() * n.z(), normal_weights_[k]});
      second_of_pair_.push_back(code < 0);
    }
    exp_minus_2sigma_ = std::exp(-2.0 * sigma_);
    double closest = -1;  // the largest cosine between two preferred normals
    for (int k = 0; k < K; ++k)
      for (int j = k + 1; j < K; ++j) closest = std::max(closest, normals_[k].dot(normals_[j]));
    separation_ = K > 1 ? sigma_ * (1.0 - closest) : INFINITY;
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
  double g;
  Eigen::Vector3d grad;
  Eigen::Matrix3d hess;
  evaluate(x, g, grad, hess);
  return g;
}

void PreferenceFunction::evaluate(const Eigen::Vector3d& x, const Eigen::Vector3d& preferred, double& g,
                                  Eigen::Vector3d& grad, Eigen::Matrix3d& hess) const {
  if (kind_ == StyleKind::directions) {
    evaluate(x, g, grad, hess);
    return;
  }
  const double s = sigma_;
  if (kind_ == StyleKind::gauss_map) {
    if (!terms_.empty()) {  // a small example: every direction summed, as a directions style
      evaluate(x, g, grad, hess);
      return;
    }
    const int k = example_->nearest(preferred);
    const Eigen::Vector3d& e = normals_[k];
    g = example_->pull()[k] * std::exp(s * (x.dot(e) - 1.0));
    grad = (s * g) * e;
    hess = (s * s * g) * (e * e.transpose());
    return;
  }
  g = std::exp(s * (x.dot(preferred) - 1.0));
  grad = (s * g) * preferred;
  hess = (s * s * g) * (preferred * preferred.transpose());
}

void PreferenceFunction::evaluate(const Eigen::Vector3d& x, double& g, Eigen::Vector3d& grad,
                                  Eigen::Matrix3d& hess) const {
  if (kind_ == StyleKind::developable) {
    // The bump around x's own direction: g = exp(sigma (|x| - 1)), with its exact derivatives.
    const double len = x.norm();
    if (!(len > 0) || !std::isfinite(len)) {
      evaluate(x, x, g, grad, hess);  // NaN or zero in, NaN or a plain value out, as the other styles
      return;
    }
    const Eigen::Vector3d u = x / len;
    evaluate(x, u, g, grad, hess);
    hess.noalias() += (sigma_ * g / len) * (Eigen::Matrix3d::Identity() - u * u.transpose());
    return;
  }
  if (kind_ == StyleKind::gauss_map && terms_.empty()) {
    // Piecewise: the bump of the example normal nearest to x (one per cell of the sphere).
    evaluate(x, x, g, grad, hess);
    return;
  }
  const double s = sigma_;
  // Discrete normals in chunks: arguments, exponentials, then the accumulation of g, its gradient
  // and the upper triangle of its Hessian from the precomputed n n^T.
  constexpr int kChunk = 32;  // even: pairs sit at even positions, so no chunk splits one
  double e[kChunk];
  double v = 0, g0 = 0, g1 = 0, g2 = 0, h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;
  const int K = static_cast<int>(terms_.size());
  for (int begin = 0; begin < K; begin += kChunk) {
    const int count = std::min(kChunk, K - begin);
    const std::array<double, 10>* t = terms_.data() + begin;
    for (int k = 0; k < count; ++k)
      e[k] = s * (x.x() * t[k][0] + x.y() * t[k][1] + x.z() * t[k][2] - 1.0);
    const char* second = second_of_pair_.data() + begin;
    for (int k = 0; k < count; ++k) {
      // e[k-1] still holds the unweighted exponential of the pair's first term. Below 1e-150 the
      // division would lose range, so such rare cases take the exponential directly.
      e[k] = (second[k] && e[k - 1] > 1e-150) ? exp_minus_2sigma_ / e[k - 1] : std::exp(e[k]);
    }
    for (int k = 0; k < count; ++k) e[k] *= t[k][9];
    for (int k = 0; k < count; ++k) {
      const double c = e[k];
      v += c;
      g0 += c * t[k][0];
      g1 += c * t[k][1];
      g2 += c * t[k][2];
      h00 += c * t[k][3];
      h01 += c * t[k][4];
      h02 += c * t[k][5];
      h11 += c * t[k][6];
      h12 += c * t[k][7];
      h22 += c * t[k][8];
    }
  }
  if (field_) {
    double sums[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    field_->accumulate(x, sums);
    v += sums[0];
    g0 += sums[1];
    g1 += sums[2];
    g2 += sums[3];
    h00 += sums[4];
    h01 += sums[5];
    h02 += sums[6];
    h11 += sums[7];
    h12 += sums[8];
    h22 += sums[9];
  }
  g = v;
  grad = Eigen::Vector3d(g0, g1, g2) * s;
  const double s2 = s * s;
  hess << h00 * s2, h01 * s2, h02 * s2, h01 * s2, h11 * s2, h12 * s2, h02 * s2, h12 * s2, h22 * s2;
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
