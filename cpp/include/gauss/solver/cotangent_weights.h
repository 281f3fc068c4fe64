#pragma once
// Rest-pose cotangent weights of one triangle (the spokes-and-rims ARAP energy, paper Eq. 2), with the
// decision whether the triangle is shaped well enough to be given them.
//
// Why the decision: the weights enter the Laplacian, the rotation fit, the ADMM normal step and the
// right-hand side (lambda w e*). A triangle with an angle near 0 or 180 degrees (a sliver: a filled
// hole's long thin fan, an n-gon with collinear sides triangulated, coordinates rounded to float)
// has huge cotangents whose values are rounding noise. Its own ARAP term stays positive
// semi-definite, but the ADMM's edge targets e* do not close around a face, and a weight of |cot|
// turns that mismatch into forces that grow like cot^2 relative to the face's stiffness, which blows
// the mesh up (measured: docs/robustness.md#what-is-refused-and-what-is-accepted).
// Such a triangle gets the same small positive weight as a zero-area one: it still ties its vertices
// to the mesh, and the Laplacian stays definite. Well-shaped meshes (every |cot| <= kMaxCotangent,
// i.e. every angle between ~0.29 and ~179.71 degrees) are not affected at all.
#include <Eigen/Core>
#include <array>

namespace gauss {

// Largest |cot| of any angle of a triangle that keeps its cotangent weights (cot 0.29 deg ~ 200).
constexpr double kMaxCotangent = 200.0;
// Weight of each edge slot of a triangle that does not keep its cotangent weights.
constexpr double kIllShapedWeight = 1e-3;

struct TriangleWeights {
  std::array<double, 3> w;  // per slot k (edge e[k], opposite corner k+2): cot(angle) / 2, or kIllShapedWeight
  bool well_shaped;         // false: zero area, or an angle with |cot| > kMaxCotangent
};

// e: the triangle's 3 edge vectors, e[k] = v[(k+1)%3] - v[k] (any finite values; zero area allowed).
TriangleWeights cotangent_weights(const Eigen::Vector3d e[3]);

}  // namespace gauss
