#include "gauss/solver/gauss_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gauss/solver/closest_rotation.h"
#include "gauss/solver/cotangent_weights.h"
#include "gauss/util/memory_budget.h"
#include "gauss/solver/normal_step.h"
#include "gauss/util/parallel.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"
#include "gauss/mesh/spatial_order.h"

namespace gauss {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Clock = std::chrono::steady_clock;

// Memory the solver keeps per face (topology, rest quantities, ADMM buffers, edges) and per vertex,
// rounded down from its members' sizes, for the early memory check. Per face, counting 1.5 edges a
// face: topology 73 bytes, rest quantities 44, styles 12, step buffers 92 (221 in all; unless the
// steps are lean 168 more: face_scratch_, slot_rest_, slot_edge_weight_); per vertex:
// numbering and topology 12, positions 72, rotations 104, the iteration's 81, the constrained
// system's 56 (325; the factor is checked on its own).
constexpr int64_t kSetupBytesPerFace = 210, kSetupBytesPerVertex = 320;

// Bending stiffness per unit area and squared curvature, of ARAP (per unit face area: kArapBending a
// kappa^2) and of the term sum_ij w_ij |R_i - R_j|^2 (kSmoothBending kappa^2), from a triangle lattice
// bent into a cylinder (docs/resolution.md#bending-araps-stiffness-shrinks-with-the-edge-length).
constexpr double kArapBending = 0.63, kSmoothBending = 2.0;

// With weigh_finer_faces, a face of zero rest area gets the coupling of one a 1e6th of the reference's:
// it stays put, as such faces should, and the factor stays finite.
constexpr double kMinAreaRatio = 1e-6;

// fit_rotations_of_start(): at most this many sweeps (each about a fifth of a step's time), stopping
// once no rotation matrix entry changes by more than kStartRotationChange in one. On a mesh 40 times
// finer than the reference (test_set_vertices.cpp) a converged result set as the start then drifts
// 1.8% of its displacement in ten steps (30 sweeps: 0.6%, none: 9%); a bake's frame on the 35K bunny
// pays 60 ms for them (30 sweeps: 120 ms, against 86 ms of set-up and 19 ms a step).
constexpr int kStartRotationSweeps = 15;
constexpr double kStartRotationChange = 1e-3;

// Square Flat Regions' pull per unit area of a face (flat_regions.h), against ARAP's covariance, which a
// face's area alone scales: strong enough to turn the walls of a round cap's rim to its axes at the
// default strengths of both methods (docs/styles.md#square-flat-regions).
constexpr double kSquarePull = 4.0;

// How many half-sizes of the reach box (gauss_solver.h) a step's result may lie from its centre before
// the step counts as running away: stylized shapes stay inside the box or close to it, and the fuzzing's
// contract allows 20 (10 sizes).
constexpr double kRunawayReach = 4.0;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace

GaussSolver::GaussSolver(const double* V, int num_vertices, const int64_t* F, int num_faces,
                         const std::vector<int64_t>& pinned, const double* pin_positions,
                         double lambda, Progress* watcher) {
  Progress unwatched;
  Progress& progress = watcher ? *watcher : unwatched;
  progress.start(SetupPhase::topology);
  if (num_vertices <= 0) throw std::invalid_argument("the mesh has no vertices");
  if (num_faces <= 0) throw std::invalid_argument("the mesh has no faces");
  settings::lambda.check(lambda);
  // The per-face and per-vertex arrays alone (a lower bound; the factor is checked once its size is
  // known): a mesh far too big for the machine is refused before anything is allocated.
  check_memory(kSetupBytesPerFace * int64_t{num_faces} + kSetupBytesPerVertex * int64_t{num_vertices},
               "a mesh of " + std::to_string(num_vertices) + " vertices and " + std::to_string(num_faces) + " faces");
  for (int i = 0; i < 3 * num_vertices; ++i)
    if (!std::isfinite(V[i])) {
      std::ostringstream msg;
      msg << "vertex " << i / 3 << " has a NaN or infinite coordinate";
      throw std::invalid_argument(msg.str());
    }
  for (int i = 0; i < 3 * num_faces; ++i)
    if (F[i] < 0 || F[i] >= num_vertices) {
      std::ostringstream msg;
      msg << "face " << i / 3 << " refers to vertex " << F[i] << ", but the mesh has " << num_vertices
          << " vertices (valid indices are 0.." << num_vertices - 1 << ")";
      throw std::invalid_argument(msg.str());
    }
  // Work in a cache-friendly numbering; the caller's numbering is restored on output. The renumbered
  // faces (24 bytes a face) are freed before the factorization, whose peak is the set-up's.
  {
    std::vector<int> face_order;
    spatial_order(V, num_vertices, F, num_faces, new_of_old_, face_order);
    std::vector<int64_t> faces(3 * static_cast<size_t>(num_faces));
    for (int f = 0; f < num_faces; ++f)
      for (int k = 0; k < 3; ++k) faces[3 * f + k] = new_of_old_[F[3 * face_order[f] + k]];
    progress.check();
    topo_ = build_mesh_topology(num_vertices, faces.data(), num_faces, &progress);
    for (int& f : topo_.input_face) f = face_order[f];
  }
  progress.enter(SetupPhase::weights);
  num_input_faces_ = num_faces;
  lambda_ = lambda;

  input_.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v)
    input_[new_of_old_[v]] = Vector3d(V[3 * v], V[3 * v + 1], V[3 * v + 2]);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = Vector3d::Constant(-INFINITY), sum = Vector3d::Zero();
  int referenced = 0;
  for (int v = 0; v < num_vertices; ++v)
    if (topo_.component[v] >= 0) {
      lo = lo.cwiseMin(input_[v]);
      hi = hi.cwiseMax(input_[v]);
      sum += input_[v];
      ++referenced;
    }
  scale_ = (hi - lo).maxCoeff();
  // Headroom: results leave the bounding box (pins up to settings::max_pin_distance sizes away).
  if (!(scale_ > 1e-300) || !(lo.minCoeff() >= -settings::max_coordinate && hi.maxCoeff() <= settings::max_coordinate) ||
      !sum.allFinite()) {
    std::ostringstream msg;
    msg << "the mesh's extent is zero or too large to represent (all vertices at one point, or coordinates beyond +-"
        << settings::max_coordinate << ")";
    throw std::invalid_argument(msg.str());
  }
  // Clamped into the bounding box: a centroid rounded outside it (all x equal, far from the origin)
  // put the normalized mesh ~1e263 from the origin, and every later sum lost all precision.
  center_ = (sum / referenced).cwiseMax(lo).cwiseMin(hi);
  rest_.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v) rest_[v] = (input_[v] - center_) / scale_;
  X_ = rest_;

  compute_rest_quantities();
  progress.check();
  // The factorization first, then the step's buffers: the factorization's peak (the factor in
  // doubles and the analysis's scratch) does not stack on them.
  apply_pins(pinned, pin_positions, progress);
  const int nF = static_cast<int>(topo_.faces.size());
  normal_star_.assign(nF, Vector3d::UnitZ());
  dual_.assign(nF, {0, 0, 0});
  face_mu_.assign(nF, 0.0);
  edge_star_.assign(topo_.edges.size(), Vector3d::Zero());
  set_lean_steps(num_vertices >= kSinglePrecisionUnknowns);
  rotation_.assign(num_vertices, Matrix3d::Identity());
  rotation_q_.assign(num_vertices, Eigen::Quaterniond::Identity());
  iteration_ = FixedPointIteration(num_vertices);

  styles_.emplace_back(default_style());
  face_style_.assign(nF, 0);
  face_weight_.assign(nF, 1.0);
  progress.finish();
}

void GaussSolver::compute_rest_quantities() {
  const int nF = static_cast<int>(topo_.faces.size());
  slot_weight_.resize(nF);
  edge_weight_.assign(topo_.edges.size(), 0.0);
  face_area_.resize(nF);
  for (int f = 0; f < nF; ++f) {
    const auto& t = topo_.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = rest_[t[(k + 1) % 3]] - rest_[t[k]];
    face_area_[f] = 0.5 * e[0].cross(e[1]).norm();
    const TriangleWeights tw = cotangent_weights(e);
    for (int k = 0; k < 3; ++k) {
      slot_weight_[f][k] = tw.w[k];
      edge_weight_[topo_.face_edge[f][k]] += tw.w[k];
    }
  }
  floor_negative_edge_weights(topo_, slot_weight_, edge_weight_);
  update_face_coupling();
}

double GaussSolver::face_coupling(int f) const {
  if (!resolution_independent_) return 1.0;
  // A face finer than the reference keeps lambda: its bending is what the setting tops up. A coupling
  // of reference/area times lambda there (weigh_finer_faces) moves the share by at most 0.015 where
  // both rules settle, but kept Tetrahedron at lambda 10 from settling on six of the corpus's meshes,
  // five of which settle without it (docs/resolution.md).
  const double floor = weigh_finer_faces_ ? kMinAreaRatio * reference_face_area_ : reference_face_area_;
  return reference_face_area_ / std::max(face_area_[f], floor);
}

void GaussSolver::update_face_coupling() {
  if (!resolution_independent_) {
    bending_beta_ = {};
    rotation_prior_ = {};
    return;
  }
  const int nF = static_cast<int>(topo_.faces.size());
  const double a_ref = reference_face_area_;
  // The bending term's beta at each vertex tops ARAP's own bending stiffness (kArapBending a kappa^2 per
  // unit area, a the local face area) up to the reference's: beta = kArapBending / kSmoothBending *
  // (a_ref - a), none where the mesh is coarser than the reference (docs/resolution.md).
  std::vector<double> area(topo_.num_vertices, 0.0);
  std::vector<int> count(topo_.num_vertices, 0);
  for (int f = 0; f < nF; ++f)
    for (int v : topo_.faces[f]) area[v] += face_area_[f], ++count[v];
  bending_beta_.assign(topo_.num_vertices, 0.0);
  for (int v = 0; v < topo_.num_vertices; ++v)
    if (count[v] > 0) bending_beta_[v] = kArapBending / kSmoothBending * std::max(0.0, a_ref - area[v] / count[v]);
}

void GaussSolver::face_pass() {
  // Algorithm 1's initialization (n* = n_f, e* = e_ij, u = 0) fused with the first round's normal
  // update, which only needs this face's own edges: the first round reads no shared array.
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_;
  const double zero[3] = {0, 0, 0};
  parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
    const auto& t = topo_.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = X_[t[(k + 1) % 3]] - X_[t[k]];
    const Vector3d c = e[0].cross(e[1]);
    const double len = c.norm();
    const double size = e[0].squaredNorm() + e[1].squaredNorm() + e[2].squaredNorm();
    const bool degenerate = !(len > 1e-12 * size) || !std::isfinite(len);
    const int s = face_style_[f];
    face_mu_[f] = degenerate || s == -1 ? 0.0 : s >= 0 ? styles_[s].mu() * face_weight_[f] : blend_mu_[-2 - s];
    dual_[f] = {0, 0, 0};
    if (face_mu_[f] > 0.0) {
      // The sign of e*_ij does not matter while u = 0 (both terms are even in e*).
      const double lam_f = lam * face_coupling(f);  // == lam when resolution_independent is off
      const double lw[3] = {lam_f * slot_edge_weight(f, 0), lam_f * slot_edge_weight(f, 1),
                            lam_f * slot_edge_weight(f, 2)};
      normal_star_[f] = normal_update(f, s, c / len, e, lw, zero);
    }
    if (!lean_steps()) face_scratch_[f] = face_covariance(f, e);
  });
}

Matrix3d GaussSolver::face_covariance(int f) const {
  const auto& t = topo_.faces[f];
  Vector3d e[3];
  for (int k = 0; k < 3; ++k) e[k] = X_[t[(k + 1) % 3]] - X_[t[k]];
  return face_covariance(f, e);
}

Matrix3d GaussSolver::vertex_covariance(int v) const {
  Matrix3d M = Matrix3d::Zero();
  for (int i = topo_.vertex_corner_start[v]; i < topo_.vertex_corner_start[v + 1]; ++i)
    M += face_covariance(topo_.vertex_corners[i] / 3);
  return M;
}

Matrix3d GaussSolver::face_covariance(int f, const Vector3d* e) const {
  Matrix3d cov = e[0] * slot_rest(f, 0).transpose();
  cov.noalias() += e[1] * slot_rest(f, 1).transpose();
  cov.noalias() += e[2] * slot_rest(f, 2).transpose();
  return cov;
}

Vector3d GaussSolver::normal_update(int f, int s, const Vector3d& n, const Vector3d* es, const double* lw,
                                    const double* u) const {
  const Vector3d* preferred = any_anchored_ ? &preferred_normal_[f] : nullptr;
  if (s >= 0) {
    if (!paper_step_any_sigma_ && takes_trust_region_step(styles_[s]))
      return trust_region_normal(styles_[s], n, es, lw, u, preferred);
    return newton_normal(styles_[s], n, es, lw, u, preferred);
  }
  const int b = -2 - s;
  const StyleShare* shares = &blend_shares_[blend_start_[b]];
  const int count = blend_start_[b + 1] - blend_start_[b];
  // A blend takes the trust-region step where one of its styles would and every one of them is of
  // fixed directions without rings.
  bool solve = false;
  for (int k = 0; k < count && !paper_step_any_sigma_; ++k) {
    const PreferenceFunction& style = styles_[shares[k].style];
    if (style.kind() != StyleKind::directions || style.has_rings()) {
      solve = false;
      break;
    }
    solve = solve || takes_trust_region_step(style);
  }
  if (solve) return trust_region_normal(styles_.data(), shares, count, n, es, lw, u, preferred);
  return newton_normal(styles_.data(), shares, count, n, es, lw, u, preferred);
}

void GaussSolver::update_preferred_normals() const {
  if (any_developable_) {
    developable_normals(topo_, X_, vertex_moment_, vertex_ruling_, preferred_normal_);
  } else if (any_anchored_) {
    // A gauss_map style's target is fixed for the step: the example normal nearest to the face's normal
    // now (as Liu & Jacobson's analogies fix theirs in the local step). A degenerate face keeps +Z.
    parallel::for_each(static_cast<int>(topo_.faces.size()), parallel::kMinParallelItems, [&](int f) {
      const auto& t = topo_.faces[f];
      const Vector3d c = (X_[t[1]] - X_[t[0]]).cross(X_[t[2]] - X_[t[0]]);
      const double len = c.norm();
      preferred_normal_[f] = (len > 0 && std::isfinite(len)) ? Vector3d(c / len) : Vector3d::UnitZ();
    });
  }
}

void GaussSolver::fit_rotations() {
  const int nV = topo_.num_vertices;
  const Matrix3d* prior = rotation_prior();
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    const int begin = topo_.vertex_corner_start[v], end = topo_.vertex_corner_start[v + 1];
    if (begin == end) return;
    Matrix3d M;
    if (lean_steps()) {
      M = vertex_covariance(v);
    } else {
      M.setZero();
      for (int i = begin; i < end; ++i) M += face_scratch_[topo_.vertex_corners[i] / 3];
    }
    if (prior) M += prior[v];
    rotation_[v] = closest_rotation_warm(M, rotation_q_[v]);
  });
}

void GaussSolver::update_square_prior() {
  if (!square_flat_regions_) {
    square_ = {};
    square_prior_ = {};
    return;
  }
  if (square_.face.empty() && square_.regions.empty()) square_ = square_targets(topo_, rest_);
  square_prior_.assign(topo_.num_vertices, Matrix3d::Zero());
  for (size_t i = 0; i < square_.face.size(); ++i) {
    const int f = square_.face[i], s = face_style_[f];
    const double mu = s == -1 ? 0.0 : s >= 0 ? styles_[s].mu() * face_weight_[f] : blend_mu_[-2 - s];
    if (!(mu > 0)) continue;
    // The fit maximizes tr(R^T M): this term rewards R near the face's squaring rotation.
    const Matrix3d pull = (kSquarePull * mu * square_.weight[i]) * square_.rotation[i];
    for (int v : topo_.faces[f]) square_prior_[v] += pull;
  }
}

double GaussSolver::rotation_prior_factor() const {
  // The cubic method's covariance weights each half-edge by the whole edge weight, twice ARAP's spokes
  // and rims, and so bends twice as stiffly: its prior is doubled to match.
  return method_ == Method::cubic ? 2.0 : 1.0;
}

EIGEN_ALWAYS_INLINE void GaussSolver::add_rotation_prior(int v, double factor, Matrix3d& P) const {
  // The bending term beta sum_ij w_ij |R_i - R_j|^2 (docs/resolution.md) adds beta w_ij R_j to vertex i's
  // rotation fit; R_j from the previous step, so that every vertex fits at once.
  if (resolution_independent_) {
    const double beta_v = bending_beta_[v];
    for (int i = topo_.vertex_corner_start[v]; i < topo_.vertex_corner_start[v + 1]; ++i) {
      const int c = topo_.vertex_corners[i], f = c / 3, k = c % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      const auto& t = topo_.faces[f];
      // Corner k heads slot k (to corner k+1) and ends slot k+2 (from corner k+2). A slot's weight
      // is beta w+: its ends' mean beta times its cotangent weight, negative ones left out (they
      // would reward bending).
      const double w_out = 0.5 * (beta_v + bending_beta_[t[k1]]) * std::max(0.0, slot_weight_[f][k]);
      const double w_in = 0.5 * (bending_beta_[t[k2]] + beta_v) * std::max(0.0, slot_weight_[f][k2]);
      P += (factor * w_out) * rotation_[t[k1]];
      P += (factor * w_in) * rotation_[t[k2]];
    }
  }
  if (square_flat_regions_) P += factor * square_prior_[v];  // its pull, in ARAP's units like the bending
}

const Matrix3d* GaussSolver::rotation_prior() {
  if (!resolution_independent_ && !square_flat_regions_) return nullptr;
  const int nV = topo_.num_vertices;
  rotation_prior_.resize(nV);
  const double factor = rotation_prior_factor();
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    Matrix3d P = Matrix3d::Zero();
    add_rotation_prior(v, factor, P);
    rotation_prior_[v] = P;
  });
  return rotation_prior_.data();
}

void GaussSolver::fit_rotations_of_start() {
  // The bending term reads the last step's rotations. A warm start's are made from its own shape, not
  // left at the rest shape's identity: on a mesh much finer than the reference face area the term
  // outweighs a vertex's own fit hundreds of times over, and identity rotations turned a whole start
  // back towards the rest shape's orientation in its first steps (a 500K-vertex sphere finished from
  // its proxy's cube look fell from a share of 0.93 to 0.45). ARAP's own fit of the shape first, then
  // Jacobi sweeps of the fit with the bending term, the shape held, towards the rotations the term
  // settles to for it (docs/resolution.md#warm-starts).
  // Each vertex's covariance is summed once, into rotation_prior_ (refilled at every step); a sweep
  // reads the neighbours' rotations of the sweep before (rotation_) and fits into rotation_q_. ARAP's
  // covariance stands in for the cubic method's, which weighs it twice (rotation_prior_factor).
  const int nV = topo_.num_vertices;
  const double factor = rotation_prior_factor();
  rotation_prior_.resize(nV);
  parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
    const Eigen::Matrix3d M = factor * vertex_covariance(v);
    rotation_prior_[v] = M;
    rotation_q_[v] = Eigen::Quaterniond(closest_rotation(M));
    rotation_[v] = rotation_q_[v].toRotationMatrix();
  });
  std::vector<double> change(nV, 0.0);
  for (int sweep = 0; sweep < kStartRotationSweeps; ++sweep) {
    parallel::for_each(nV, parallel::kMinParallelItems, [&](int v) {
      Eigen::Matrix3d prior = Eigen::Matrix3d::Zero(), R = rotation_[v];
      add_rotation_prior(v, factor, prior);
      closest_rotation_warm(rotation_prior_[v] + prior, rotation_q_[v], R);
      change[v] = (R - rotation_[v]).cwiseAbs().maxCoeff();
    });
    parallel::for_each(nV, parallel::kMinParallelItems,
                       [&](int v) { rotation_[v] = rotation_q_[v].toRotationMatrix(); });
    if (*std::max_element(change.begin(), change.end()) < kStartRotationChange) break;
  }
}

void GaussSolver::admm_round(bool first_round) {
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_;
  // Normals (Eqs. 17-22): the first round's update happened in face_pass(). Later rounds start with
  // the previous round's dual update (Eq. 25).
  if (!first_round) {
    parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
      if (face_mu_[f] == 0.0) return;
      const Vector3d n = normal_star_[f];
      const auto& fe = topo_.face_edge[f];
      const Vector3d es[3] = {edge_star_[fe[0]], edge_star_[fe[1]], edge_star_[fe[2]]};
      for (int k = 0; k < 3; ++k) dual_[f][k] += es[k].dot(n);
      const double lam_f = lam * face_coupling(f);
      const double lw[3] = {lam_f * slot_edge_weight(f, 0), lam_f * slot_edge_weight(f, 1),
                            lam_f * slot_edge_weight(f, 2)};
      normal_star_[f] = normal_update(f, face_style_[f], n, es, lw, dual_[f].data());
    });
  }
  // Edges (Eq. 24): (I + sum mu n n^T) e* = e - sum mu u n over the styled faces of the edge.
  const int nE = static_cast<int>(topo_.edges.size());
  parallel::for_each(nE, parallel::kMinParallelItems, [&](int e) {
    const Vector3d cur = X_[topo_.edges[e][1]] - X_[topo_.edges[e][0]];
    // Collect the styled faces (usually one or two; more on non-manifold edges).
    int count = 0;
    double mu[2];
    const Vector3d* nrm[2];
    Vector3d b = cur;
    for (int i = topo_.edge_slot_start[e]; i < topo_.edge_slot_start[e + 1]; ++i) {
      const int f = topo_.edge_slots[i] / 3, k = topo_.edge_slots[i] % 3;
      const double m = face_mu_[f];
      if (m == 0.0) continue;
      const Vector3d& n = normal_star_[f];
      b -= (m * dual_[f][k]) * n;
      if (count < 2) {
        mu[count] = m;
        nrm[count] = &n;
      }
      ++count;
    }
    if (count == 0) {
      edge_star_[e] = cur;
    } else if (count == 1) {  // Sherman-Morrison: (I + m n n^T)^-1 b = b - m (n.b) / (1 + m) n
      edge_star_[e] = b - (mu[0] * nrm[0]->dot(b) / (1.0 + mu[0])) * *nrm[0];
    } else if (count == 2) {  // Woodbury with the 2x2 system (I + D N^T N) y = D N^T b
      const Vector3d &n0 = *nrm[0], &n1 = *nrm[1];
      const double c = n0.dot(n1), r0 = mu[0] * n0.dot(b), r1 = mu[1] * n1.dot(b);
      const double a00 = 1.0 + mu[0], a01 = mu[0] * c, a10 = mu[1] * c, a11 = 1.0 + mu[1];
      const double det = a00 * a11 - a01 * a10;  // >= 1 + mu0 + mu1 > 0 for unit normals
      const double y0 = (a11 * r0 - a01 * r1) / det, y1 = (a00 * r1 - a10 * r0) / det;
      edge_star_[e] = b - y0 * n0 - y1 * n1;
    } else {  // non-manifold: the 3x3 system itself, built only here (the common cases never read it)
      Matrix3d A = Matrix3d::Identity();
      for (int i = topo_.edge_slot_start[e]; i < topo_.edge_slot_start[e + 1]; ++i) {
        const int f = topo_.edge_slots[i] / 3;
        if (face_mu_[f] != 0.0) A.noalias() += face_mu_[f] * (normal_star_[f] * normal_star_[f].transpose());
      }
      Vector3d x;
      edge_star_[e] = solve_symmetric3(A, b, x) ? x : cur;  // A >= I: always solvable
    }
  });
}

void GaussSolver::update_reach() {
  // Vertices no face uses are left out: they never move, and one far away must not widen the box.
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < topo_.num_vertices; ++v)
    if (topo_.component[v] >= 0) lo = lo.cwiseMin(rest_[v]).cwiseMin(X_[v]), hi = hi.cwiseMax(rest_[v]).cwiseMax(X_[v]);
  for (const Vector3d& t : pin_targets_) {
    const Vector3d p = (t - center_) / scale_;
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  if (!(lo.array() <= hi.array()).all()) lo = hi = Vector3d::Zero();  // no face: nothing moves
  reach_centre_ = 0.5 * (lo + hi);
  reach_ = std::max(0.5 * (hi - lo).maxCoeff(), 1e-12);
}

bool GaussSolver::ran_away() const {
  const double limit = kRunawayReach * reach_;
  for (int v = 0; v < topo_.num_vertices; ++v)
    if (topo_.component[v] >= 0 && !((X_[v] - reach_centre_).cwiseAbs().maxCoeff() <= limit)) return true;  // NaN too
  return false;
}

void GaussSolver::assemble_rhs(Rhs terms) {
  if (terms == Rhs::cubic) {  // the cubic method: plain ARAP's global step, the same sum folded per vertex
    parallel::for_each(laplacian_.num_unknowns(), parallel::kMinParallelItems, [&](int u) {
      laplacian_.set_rhs(u, laplacian_.constant_rhs(u) + cubic_.global_rhs(laplacian_.vertex_of_unknown(u), rotation_));
    });
    return;
  }
  if (lean_steps()) {
    assemble_rhs_lean(terms);
    return;
  }
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_, inv = 1.0 / (1.0 + lambda_);
  parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
    const Matrix3d Rf = face_rotation(f);
    Vector3d d[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = Rf * slot_rest_[f][k];
      if (terms == Rhs::arap) continue;
      const double s = topo_.face_edge_sign[f][k];
      d[k] = (d[k] + (lam * slot_weight_[f][k] * s) * edge_star_[topo_.face_edge[f][k]]) * inv;
    }
    // Corner k is the head of slot k-1 and the tail of slot k.
    for (int k = 0; k < 3; ++k) face_scratch_[f].col(k) = d[(k + 2) % 3] - d[k];
  });
  parallel::for_each(laplacian_.num_unknowns(), parallel::kMinParallelItems, [&](int u) {
    const int v = laplacian_.vertex_of_unknown(u);
    Vector3d b = laplacian_.constant_rhs(u);
    for (int i = topo_.vertex_corner_start[v]; i < topo_.vertex_corner_start[v + 1]; ++i) {
      const int c = topo_.vertex_corners[i];
      b += face_scratch_[c / 3].col(c % 3);
    }
    laplacian_.set_rhs(u, b);
  });
}

void GaussSolver::assemble_rhs_lean(Rhs terms) {
  // assemble_rhs()'s sum, each corner's share computed where it is added: the same operations on
  // the same values, so the same bits (the test LeanStepsGiveTheSameBits holds the two together).
  const double lam = lambda_, inv = 1.0 / (1.0 + lambda_);
  parallel::for_each(laplacian_.num_unknowns(), parallel::kMinParallelItems, [&](int u) {
    const int v = laplacian_.vertex_of_unknown(u);
    Vector3d b = laplacian_.constant_rhs(u);
    for (int i = topo_.vertex_corner_start[v]; i < topo_.vertex_corner_start[v + 1]; ++i) {
      const int c = topo_.vertex_corners[i], f = c / 3;
      const Matrix3d Rf = face_rotation(f);
      Vector3d d[2];
      const int slots[2] = {(c % 3 + 2) % 3, c % 3};  // corner k: the head of slot k-1, the tail of slot k
      for (int h = 0; h < 2; ++h) {
        const int k = slots[h];
        d[h] = Rf * slot_rest(f, k);
        if (terms == Rhs::arap) continue;
        const double s = topo_.face_edge_sign[f][k];
        d[h] = (d[h] + (lam * slot_weight_[f][k] * s) * edge_star_[topo_.face_edge[f][k]]) * inv;
      }
      b += d[0] - d[1];
    }
    laplacian_.set_rhs(u, b);
  });
}

Matrix3d GaussSolver::face_rotation(int f) const {
  // Spokes and rims: every vertex of the face rotates the face's three edges, so the ARAP target
  // of an edge is the mean rotation of the face applied to its rest vector (Eq. 27).
  const auto& t = topo_.faces[f];
  return (rotation_[t[0]] + rotation_[t[1]] + rotation_[t[2]]) * (1.0 / 3.0);
}

void GaussSolver::local_global_step() {
  auto t0 = Clock::now();
  const bool gauss = method_ == Method::gauss;
  if (gauss) {
    update_preferred_normals();
    face_pass();
    timings_.faces = ms_since(t0);
    t0 = Clock::now();
    fit_rotations();
    timings_.rotations = ms_since(t0);
    t0 = Clock::now();
    // The last round's dual update is skipped: duals are re-initialized at the next step and the
    // global step does not read them.
    for (int r = 0; r < admm_iterations_; ++r) admm_round(r == 0);
  } else {
    cubic_.covariances(topo_, X_, face_scratch_);
    timings_.faces = ms_since(t0);
    timings_.rotations = 0;
    t0 = Clock::now();
    // One flag for all vertices: the cubic momentum holds no vertex back, so every vertex's state
    // was extrapolated (or none was).
    static_assert(settings::cubic_momentum.hold == 0, "fit() would need to know which vertices were held");
    cubic_.fit(topo_, face_scratch_, cubic_lambda_, iteration_.extrapolated(), rotation_, rotation_q_,
               rotation_prior());
  }
  timings_.admm = ms_since(t0);
  t0 = Clock::now();
  assemble_rhs(gauss ? Rhs::gauss : Rhs::cubic);
  timings_.rhs = ms_since(t0);
  t0 = Clock::now();
  if (guard_ && springs_.active()) springs_.solve(laplacian_, X_);
  else laplacian_.solve(X_);
  timings_.solve = ms_since(t0);
}

void GaussSolver::step() {
  const int threads = tuner_.next(parallel::max_threads());
  const parallel::ScopedThreads scoped(threads);
  const auto start = Clock::now();
  // The normalized frame's longest bounding-box side is 1.
  // The guard compares the step's result with the iterate before it (not with an extrapolated
  // point, which may itself be in contact).
  if (guard_) safe_ = X_;
  const auto map = [this] {
    local_global_step();
    // The edge pull is a contraction when the cotangent weights are positive; where enough of them are
    // negative (obtuse, non-Delaunay patches) it can amplify the iterate from step to step. Such a step
    // is redone without the pull: plain ARAP with the rotations just fitted, which does not read the iterate.
    if (method_ == Method::gauss && ran_away()) {
      assemble_rhs(Rhs::arap);
      laplacian_.solve(X_);
      ++runaway_steps_;
    }
    if (keep_volume_) volume_.restore(topo_, X_);
    if (guard_) {
      const auto guard_start = Clock::now();
      guard_->limit(safe_, X_);
      timings_.guard = ms_since(guard_start);
    }
  };
  if (method_ == Method::cubic) iteration_.advance(X_, cubic_.carried_state(), rest_, 1.0, map);
  else iteration_.advance(X_, rest_, 1.0, map);
  if (guard_ && springs_.stiffness() > 0) springs_.note_held(guard_->last_held_vertices(), X_, laplacian_, topo_);
  denied_reldv_ = 0;
  if (guard_ && guard_->last_held() > 0) {  // measured as reldV is: over the largest displacement
    double displacement = kStillDisplacement;
    for (size_t v = 0; v < X_.size(); ++v) displacement = std::max(displacement, (X_[v] - rest_[v]).cwiseAbs().maxCoeff());
    denied_reldv_ = guard_->last_denied() / displacement;
  }
  ++step_count_;
  tuner_.record(threads, ms_since(start));
  timings_.threads = threads;
}

int GaussSolver::step_until(double tolerance, int max_steps) {
  if (max_steps < 0) throw std::invalid_argument("the number of steps must be >= 0");
  set_tolerance(tolerance);
  int taken = 0;
  while (taken < max_steps && last_reldv() >= tolerance_) {  // until converged or held back
    step();
    ++taken;
  }
  return taken;
}

void GaussSolver::set_tolerance(double tolerance) {
  settings::tolerance.check(tolerance);
  tolerance_ = tolerance;
}

void GaussSolver::reset() {
  X_ = rest_;
  // The rotation warm start is state too: a reset run must repeat the first run bit for bit.
  std::fill(rotation_q_.begin(), rotation_q_.end(), Eigen::Quaterniond::Identity());
  std::fill(rotation_.begin(), rotation_.end(), Matrix3d::Identity());  // the bending term reads the last step's
  if (cubic_ready_) cubic_.reset();
  laplacian_.place_pins(X_);
  if (guard_) guard_->start_from(X_);
  springs_.clear();
  update_reach();
  step_count_ = 0;
  runaway_steps_ = 0;
  iteration_.invalidate();
}

}  // namespace gauss
