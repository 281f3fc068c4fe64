#pragma once
// The rotation part of a 3x3 matrix: R = argmax_{R in SO(3)} tr(R^T M), i.e. the polar factor of M
// with the reflection case folded into the smallest singular direction (as in ARAP's local step).
//
// Why not a general SVD: this runs once per vertex per step. The symmetric eigenproblem of M^T M is
// solved by cyclic Jacobi rotations (exact, a handful of sweeps), then U's first two columns are
// M v1, M v2 orthonormalized and the third columns are cross products, which makes det(R) = +1 by
// construction and keeps rank-2 covariances (flat neighbourhoods, common in stylized output) exact.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <utility>

namespace gauss {

inline Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& M) {
  using Eigen::Matrix3d;
  using Eigen::Vector3d;
  Matrix3d S = M.transpose() * M;
  Matrix3d V = Matrix3d::Identity();
  const double scale = S.trace();
  if (!(scale > 1e-300) || !std::isfinite(scale)) return Matrix3d::Identity();
  for (int sweep = 0; sweep < 16; ++sweep) {
    const double off = S(0, 1) * S(0, 1) + S(0, 2) * S(0, 2) + S(1, 2) * S(1, 2);
    if (off <= 1e-32 * scale * scale) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double spq = S(p, q);
        if (spq == 0.0) continue;
        const double theta = (S(q, q) - S(p, p)) / (2.0 * spq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        // S <- J^T S J, V <- V J with the Givens rotation J in the (p, q) plane.
        for (int k = 0; k < 3; ++k) {
          const double skp = S(k, p), skq = S(k, q);
          S(k, p) = c * skp - s * skq;
          S(k, q) = s * skp + c * skq;
        }
        for (int k = 0; k < 3; ++k) {
          const double spk = S(p, k), sqk = S(q, k);
          S(p, k) = c * spk - s * sqk;
          S(q, k) = s * spk + c * sqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = V(k, p), vkq = V(k, q);
          V(k, p) = c * vkp - s * vkq;
          V(k, q) = s * vkp + c * vkq;
        }
      }
  }
  // Order the eigenvalues: i0 largest, i1 second.
  int i0 = 0, i1 = 1, i2 = 2;
  if (S(i1, i1) > S(i0, i0)) std::swap(i0, i1);
  if (S(i2, i2) > S(i0, i0)) std::swap(i0, i2);
  if (S(i2, i2) > S(i1, i1)) std::swap(i1, i2);
  const Vector3d v1 = V.col(i0), v2 = V.col(i1);
  const Vector3d v3 = v1.cross(v2);
  const Vector3d b1 = M * v1;
  const double n1 = b1.norm();
  if (!(n1 > 1e-300)) return Matrix3d::Identity();
  const Vector3d u1 = b1 / n1;
  Vector3d u2 = M * v2;
  u2 -= u1.dot(u2) * u1;
  const double n2 = u2.norm();
  if (n2 > 1e-12 * n1) {
    u2 /= n2;
  } else {  // rank one: any rotation taking v1 to u1 is optimal; keep v2's direction as far as possible
    u2 = v2 - u1.dot(v2) * u1;
    if (u2.norm() < 1e-6) u2 = u1.unitOrthogonal();
    u2.normalize();
  }
  const Vector3d u3 = u1.cross(u2);
  return u1 * v1.transpose() + u2 * v2.transpose() + u3 * v3.transpose();
}

// The same rotation, found by Newton's method on SO(3) started from last step's rotation `q` (updated
// in place). Maximizing tr((R e^[w])^T M) to second order gives w = (tr(P) I - P)^-1 axial(A - A^T)
// with A = R^T M, P = sym(A); the iteration converges quadratically, and at the fixed point A is
// symmetric with tr(P) I - P positive definite, which characterizes the maximum. Between two steps
// rotations move little, so two iterations usually suffice: several times cheaper than the Jacobi
// solve above, which remains the fallback whenever Newton is not safely inside the basin.
//
// R: on entry q's rotation matrix (q.toRotationMatrix(), which a caller fitting again from the last
// result already holds), on return the result, q's rotation matrix again (or the fallback's).
//
// closest_rotation_warm_lanes<L> runs L independent fits in lockstep (lane l only if active[l]; an
// inactive lane's M, q, R are not read or written), each with exactly the operations of one fit, so
// the results are the same bits. Why: one fit is a chain of dependent operations (a product, a 3x3
// solve, a division, a square root, per iteration) whose latency the processor cannot hide on its
// own; two chains side by side overlap, and two fits take 0.78 of the time of two one after another.
template <int L>
inline void closest_rotation_warm_lanes(const Eigen::Matrix3d* M, Eigen::Quaterniond* q, Eigen::Matrix3d* R,
                                        const bool* active) {
  using Eigen::Matrix3d;
  using Eigen::Vector3d;
  bool running[L], fallback[L];
  double scale[L];
  bool any = false;
  for (int l = 0; l < L; ++l) {
    running[l] = active[l];
    fallback[l] = false;
    if (!running[l]) continue;
    scale[l] = M[l].cwiseAbs().maxCoeff();
    if (!(scale[l] > 1e-300) || !std::isfinite(scale[l])) {
      q[l] = Eigen::Quaterniond::Identity();
      R[l].setIdentity();
      running[l] = false;
    }
    any = any || running[l];
  }
  for (int it = 0; it < 8 && any; ++it) {
    any = false;
    for (int l = 0; l < L; ++l) {
      if (!running[l]) continue;
      const Matrix3d A = R[l].transpose() * M[l];
      const Vector3d a(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
      const double tr = A.trace();
      // H = tr(P) I - P, symmetric.
      const double h00 = tr - A(0, 0), h11 = tr - A(1, 1), h22 = tr - A(2, 2);
      const double h01 = -0.5 * (A(0, 1) + A(1, 0)), h02 = -0.5 * (A(0, 2) + A(2, 0)),
                   h12 = -0.5 * (A(1, 2) + A(2, 1));
      const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
      const double det = h00 * c00 + h01 * c01 + h02 * c02;
      const double minor2 = h00 * h11 - h01 * h01;
      const double sc = scale[l];
      if (!(h00 > 0 && minor2 > 0 && det > 1e-12 * sc * sc * sc)) {  // not in the basin
        running[l] = false;
        fallback[l] = true;
        continue;
      }
      const double c11 = h00 * h22 - h02 * h02, c12 = h01 * h02 - h00 * h12;
      const Vector3d w = Vector3d(c00 * a.x() + c01 * a.y() + c02 * a.z(),
                                  c01 * a.x() + c11 * a.y() + c12 * a.z(),
                                  c02 * a.x() + c12 * a.y() + minor2 * a.z()) / det;
      if (!w.allFinite()) {
        running[l] = false;
        fallback[l] = true;
        continue;
      }
      q[l] = (q[l] * Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z())).normalized();
      R[l] = q[l].toRotationMatrix();
      // Quadratic convergence: after a step of size |w| < 1e-4 the remaining error is ~1e-8 rad, far
      // below what the ARAP fit needs (reference implementations use single-precision SVDs), and a
      // vertex whose frame barely turned since the last step is done after one iteration.
      if (w.squaredNorm() < 1e-8) running[l] = false;
      any = any || running[l];
    }
  }
  for (int l = 0; l < L; ++l)
    if (fallback[l] || running[l]) {  // left the basin, or 8 iterations were not enough
      R[l] = closest_rotation(M[l]);
      q[l] = Eigen::Quaterniond(R[l]);
    }
}

inline void closest_rotation_warm(const Eigen::Matrix3d& M, Eigen::Quaterniond& q, Eigen::Matrix3d& R) {
  const bool active = true;
  closest_rotation_warm_lanes<1>(&M, &q, &R, &active);
}

inline Eigen::Matrix3d closest_rotation_warm(const Eigen::Matrix3d& M, Eigen::Quaterniond& q) {
  Eigen::Matrix3d R = q.toRotationMatrix();
  closest_rotation_warm(M, q, R);
  return R;
}

}  // namespace gauss
