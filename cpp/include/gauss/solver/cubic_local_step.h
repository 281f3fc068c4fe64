#pragma once
// The local step of Cubic Stylization (Liu & Jacobson, SIGGRAPH Asia 2019): for every vertex i,
//   R_i = argmin_R  sum_{faces f of i} sum_{edges jk of f} w_jk / 2 ||R d^_jk - d_jk||^2
//                   + lambda_i ||Q_i^T R n_i||_1
// with d^ the rest and d the current edge vectors, w_jk the edge's whole cotangent weight (the sum
// over both of its faces: the reference implementation's weights, see below), n_i the area-weighted
// unit normal of the rest mesh at i, lambda_i = lambda * a_i * m_i (a_i the barycentric area, m_i the
// style strength) and Q_i the style's orientation (the cube's axes).
//
// Solved per vertex by ADMM on (R, z = Q^T R n, u): R by the closest rotation to
// M = sum w d d^^T + rho Q (z - u) n^T, z by soft thresholding, u += Q^T R n - z, rho by residual
// balancing (mu 10, tau 2); stopped when both residuals fall below the reference's tolerances. The
// state z, u, rho is kept per vertex from one step to the next (warm start).
//
// Faithful to the reference implementation (github HTDerekLiu/CubicStylization_Cpp): its covariance
// weights every half-edge of a vertex's faces by the Laplacian's whole edge weight L_jk (not by the
// face's half of it, as ARAP's spokes-and-rims energy would), its tolerances and caps are the
// constants below, and lambda means the same in a frame normalized to a unit bounding box. It differs
// in two choices: rho is not rebalanced on the iteration that meets the stopping rule, nor on the
// first iteration at a state an accelerated iteration extrapolated (see fit()). And
// where the reference has no answer: a vertex whose ADMM does not meet the tolerances within the
// iteration cap keeps its last iterate (the reference then leaves that rotation uninitialized and
// its state unsaved), a vertex without a normal (zero-area star) or with lambda_i = 0 takes the plain
// ARAP rotation, rho stays within [kMinRho, kMaxRho], and the start is z = Q^T n, u = 0 (the
// reference starts from random z and u; the rest pose's own dual, u = lambda_i / rho sign(Q^T n),
// converged further from the reference and more slowly: docs/performance.md#fidelity-to-the-cubic-reference).
//
// Usage (geometry-central style: set-up in the constructor, no allocation in fit()):
//   CubicLocalStep cubic(topo, rest, edge_weight);
//   cubic.set_vertex_styles(strength, frame_of_vertex, frames);   // when styles change
//   per step: cubic.covariances(topo, X, cov); cubic.fit(topo, cov, lambda, extrapolated, R, q);  // then ARAP's global step
// (cov: #F Matrix3d the caller owns, scratch between the two calls; the Gauss solver lends the buffer
// its own local step uses, so the cubic method needs no second #F array.)
//   then, for the global step's right-hand side: b_v = cubic.global_rhs(v, R) for each unknown v.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "gauss/mesh/mesh_topology.h"

namespace gauss {

namespace cubic_admm {
// rho of a vertex's first ADMM iteration: kRhoPerArea times its barycentric area a_i (in the
// normalized frame), at most kRhoInit (the reference's fixed start), because the ARAP covariance and
// lambda_i both scale with a_i, so on a fine mesh a fixed start outweighs them and the run stops before
// it converged; the cap keeps coarse meshes on the start that already converged there. The figures:
// docs/performance.md#fidelity-to-the-cubic-reference.
inline constexpr double kRhoPerArea = 4.0;
inline constexpr double kRhoInit = 1e-3;
inline constexpr double kAbsTol = 1e-5;    // absolute tolerance of both residuals
inline constexpr double kRelTol = 1e-3;    // relative tolerance of both residuals
inline constexpr double kMu = 10.0;        // residual balancing: change rho when one residual is kMu times the other
inline constexpr double kTau = 2.0;        // ... by this factor
inline constexpr int kMaxIterations = 100; // per vertex and step
// Safety bounds (not in the reference), far outside where rho settles
// (docs/performance.md#fidelity-to-the-cubic-reference).
inline constexpr double kMinRho = 1e-12, kMaxRho = 1e12;
}  // namespace cubic_admm

class CubicLocalStep {
 public:
  CubicLocalStep() = default;

  // topo         the solver's mesh (faces #F by 3, vertex -> corners)
  // rest         #V by 3 rest positions in the solver's normalized frame (unit bounding box)
  // edge_weight  #E whole cotangent weights w_jk of the edges (topo.edges)
  // slot_weight  #F by 3: each face's slot weights (cotangent_weights.h, floors included), summing to
  //              edge_weight: the global step's right-hand side must use the Laplacian's weights
  CubicLocalStep(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& rest,
                 const std::vector<double>& edge_weight, const std::vector<std::array<double, 3>>& slot_weight);

  // Bytes the constructor allocates for a mesh of this size (its members and its one #F temporary,
  // rounded up): for a memory check before it runs.
  static int64_t bytes_needed(int num_vertices, int num_faces);
  // Rows of carried_state() per vertex.
  static constexpr int kCarriedPerVertex = 2;

  // strength  #V style strength m_i of each vertex (>= 0; lambda_i = lambda * a_i * m_i)
  // frame     #V index into frames of each vertex's cube orientation Q_i
  // frames    rotation matrices (each orthonormal, det +1)
  // Keeps the ADMM state; z and the dual are re-expressed in a vertex's new frame.
  void set_vertex_styles(const std::vector<double>& strength, const std::vector<int>& frame,
                         const std::vector<Eigen::Matrix3d>& frames);

  // The ADMM state back to its start (z = Q^T n, u = 0, rho = min(kRhoPerArea a_i, kRhoInit)).
  void reset();

  // A local step in two parts, each parallel, the same for any thread count, without allocation.
  // covariances: the ARAP covariance sum_k d_k (w d^_k)^T of every face from the current vertices X
  // (#V by 3, normalized frame), written to face_cov (#F, sized by the caller). fit: with those and
  // the global lambda, rotation (#V) receives each referenced vertex's R_i; rotation_q (#V) is the
  // rotation fit's warm start, read and updated. extrapolated: an accelerated iteration moved the
  // carried state ahead (then rho is not rebalanced on the first ADMM iteration, whose residuals
  // measure that move).
  void covariances(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& X,
                   std::vector<Eigen::Matrix3d>& face_cov) const;
  // prior (optional): #V matrices added to each vertex's covariance (a bending term's pull).
  void fit(const MeshTopology& topo, const std::vector<Eigen::Matrix3d>& face_cov, double lambda, bool extrapolated,
           std::vector<Eigen::Matrix3d>& rotation, std::vector<Eigen::Quaterniond>& rotation_q,
           const Eigen::Matrix3d* prior = nullptr);

  // The ADMM state a step carries to the next, #V by 2: [2i] z_i, [2i+1] rho_i u_i (the unscaled
  // dual, which a change of rho leaves alone). The solver's iteration extrapolates it together with
  // the vertices (fixed_point_iteration.h); any finite values are a valid warm start.
  std::vector<Eigen::Vector3d>& carried_state() { return carried_; }

  // Read-outs: ADMM iterations of the last fit() summed over the vertices that ran one; the cubic
  // term sum_i lambda_i ||Q_i^T R_i n_i||_1 of the given rotations (#V).
  long long last_admm_iterations() const;
  double cubic_energy(double lambda, const std::vector<Eigen::Matrix3d>& rotation) const;

  // The right-hand side of ARAP's global step at vertex v (paper Eq. 27 without the edge term), given
  // every vertex's rotation R (#V): the sum over v's faces f of R_f (w d^_prev - w d^_next), with R_f
  // the mean rotation of f's three vertices, d^_prev and d^_next the rest edges of f that end and
  // start at v, and w the face's slot weights (cotangent_weights.h, the Laplacian's).
  // Each face's share is linear in its three rotations, so the sum folds into one rest vector per
  // vertex m of v's star (m = v included): b_v = sum_m R_m g_vm. Why: this reads #V rotations and
  // ~7 precomputed vectors per vertex instead of writing and reading back a 3x3 block per face
  // (docs/performance.md#per-iteration-against-the-cubic-reference). Equal to it up to rounding.
  Eigen::Vector3d global_rhs(int v, const std::vector<Eigen::Matrix3d>& rotation) const {
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int i = star_start_[v]; i < star_start_[v + 1]; ++i) b.noalias() += rotation[star_[i].vertex] * star_[i].rest;
    return b;
  }

  const std::vector<Eigen::Vector3d>& vertex_normals() const { return normal_; }  // #V, unit or zero
  const std::vector<double>& vertex_areas() const { return area_; }               // #V barycentric

 private:
  void build_global_rhs_stars(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& rest,
                              const std::vector<std::array<double, 3>>& slot_weight);

  std::vector<Eigen::Vector3d> normal_;                       // #V n_i (zero where undefined)
  std::vector<double> area_;                                  // #V a_i
  std::vector<double> weight_;                                // #V a_i * m_i (zero where n_i is)
  std::vector<int> frame_;                                    // #V
  std::vector<Eigen::Matrix3d> frames_;                       // Q
  std::vector<char> frame_is_identity_;                       // per frame: Q == I (skips two products)
  std::vector<std::array<Eigen::Vector3d, 3>> slot_rest_;     // #F by 3: w_jk d^_jk of each slot
  std::vector<Eigen::Vector3d> carried_;                      // #V by 2: z (= Q^T R n at convergence), rho u
  std::vector<double> rho_;                                   // #V
  std::vector<int> iterations_;                               // #V, of the last fit (0: plain ARAP rotation)
  struct StarTerm {
    Eigen::Vector3d rest;  // g_vm (global_rhs)
    int vertex;            // m
  };
  std::vector<int> star_start_;                               // #V + 1: v's terms are star_[start[v], start[v+1])
  std::vector<StarTerm> star_;                                // ~7 per vertex, by vertex index within a star
};

}  // namespace gauss
