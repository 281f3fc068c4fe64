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
// to the mesh, and the Laplacian stays definite. An edge with a strongly negative weight gets it too
// (floor_negative_edge_weights, below). Well-shaped meshes (every |cot| <= kMaxCotangent, i.e. every
// angle between ~0.29 and ~179.71 degrees, and every edge weight >= kMinEdgeWeight) are not affected
// at all.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "gauss/mesh/mesh_topology.h"

namespace gauss {

// Largest |cot| of any angle of a triangle that keeps its cotangent weights (cot 0.29 deg ~ 200).
constexpr double kMaxCotangent = 200.0;
// Weight of each edge slot of a triangle that does not keep its cotangent weights.
constexpr double kIllShapedWeight = 1e-3;
// Lowest weight an edge keeps (the sum of its slots' cot / 2). Edges whose two opposite angles sum to
// more than 180 degrees have a negative weight, and Eq. 6's edge pull lambda w / 2 |e - e*|^2 is then
// no penalty: the edge step and the normal step, derived for w > 0, push such an edge away from its
// target. Where the neighbours' positive weights dominate, the run settles all the same (2-14% of the
// edges of the meshes in ../shared/meshes are negative: down to -0.6 on Spot, -3.6 on the 43K
// armadillo scan). Below -5 one of the edge's two opposite angles exceeds ~169 degrees (its cotangent
// is below -5), the cap of a hole filler's fan or of a scan's seam: a few such edges (7 of the
// hole-filled bunny's 104K, 9 of the camel head's 34K below -10) kept those meshes from ever
// settling, their fill moving up to a tenth of the mesh's size at every step; with them floored both
// settle in about 100 steps (docs/robustness.md).
constexpr double kMinEdgeWeight = -5.0;

struct TriangleWeights {
  std::array<double, 3> w;  // per slot k (edge e[k], opposite corner k+2): cot(angle) / 2, or kIllShapedWeight
  bool well_shaped;         // false: zero area, or an angle with |cot| > kMaxCotangent
};

// e: the triangle's 3 edge vectors, e[k] = v[(k+1)%3] - v[k] (any finite values; zero area allowed).
TriangleWeights cotangent_weights(const Eigen::Vector3d e[3]);

// Gives every edge whose weight is below kMinEdgeWeight the weight of an ill-shaped triangle's edge:
// kIllShapedWeight, shared evenly among the edge's slots, so that every slot weight still sums to its
// edge's. Edges at or above the limit are not touched (bit for bit).
//   topo         the mesh (edge_slot_start, edge_slots: the slots f * 3 + k of each edge)
//   slot_weight  #F by 3: slot k of face f's weight (cotangent_weights' w), updated in place
//   edge_weight  #E: the sum of each edge's slot weights, updated in place
// Returns the number of edges changed.
int floor_negative_edge_weights(const MeshTopology& topo, std::vector<std::array<double, 3>>& slot_weight,
                                std::vector<double>& edge_weight);

}  // namespace gauss
