#include "gauss/gauss_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>


#include "gauss/closest_rotation.h"
#include "gauss/memory_budget.h"
#include "gauss/parallel.h"
#include "gauss/presets.h"
#include "gauss/settings.h"
#include "gauss/spatial_order.h"

namespace gauss {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Clock = std::chrono::steady_clock;

// A face whose doubled area is below this fraction of its summed squared edge lengths has no
// reliable cotangents (|cot| would exceed ~1e8) or normal.
constexpr double kDegenerateRatio = 1e-8;
// Cotangent weight given to each edge of a face that is degenerate in the rest pose: small and
// positive, so the face still ties its vertices to the mesh and the Laplacian stays definite.
constexpr double kDegenerateWeight = 1e-3;

// Memory the solver keeps per face (topology, rest quantities, ADMM buffers, edges) and per vertex,
// rounded down from its members' sizes, for the early memory check.
constexpr int64_t kSetupBytesPerFace = 400, kSetupBytesPerVertex = 200;

// Below this many items a loop runs on one thread: forking costs more than it saves, and on a
// loaded machine (Blender's own threads) spinning workers can cost far more.
constexpr int kParallelMin = 4096;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Solves the symmetric 3x3 system H x = b by cofactors; false if H is (numerically) singular.
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

// One Newton update of a face's auxiliary normal n* (Eqs. 17-22): minimize
// L_n = -g(n) + lambda sum_k w_k/2 (u_k + n.e*_k)^2 over unit n. es: the face's three e*_ij,
// lw: lambda * w_ij of each, u: the scaled duals. Returns the new unit normal (n if no step).
Vector3d newton_normal(const PreferenceFunction& style, const Vector3d& n, const Vector3d* es, const double* lw,
                       const double* u) {
  double g;
  Vector3d grad_g;
  Matrix3d hess_g;
  style.evaluate(n, g, grad_g, hess_g);
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
  // Work in a cache-friendly numbering; the caller's numbering is restored on output.
  std::vector<int> face_order;
  spatial_order(V, num_vertices, F, num_faces, new_of_old_, face_order);
  std::vector<int64_t> faces(3 * static_cast<size_t>(num_faces));
  for (int f = 0; f < num_faces; ++f)
    for (int k = 0; k < 3; ++k) faces[3 * f + k] = new_of_old_[F[3 * face_order[f] + k]];
  progress.check();
  topo_ = build_mesh_topology(num_vertices, faces.data(), num_faces, &progress);
  progress.enter(SetupPhase::weights);
  for (int& f : topo_.input_face) f = face_order[f];
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
  // Headroom: results leave the bounding box (pins up to 1e12 sizes away), and near 1e308 the output
  // x * scale + center overflowed to infinity.
  if (!(scale_ > 1e-300) || !(lo.minCoeff() >= -1e200 && hi.maxCoeff() <= 1e200) || !sum.allFinite())
    throw std::invalid_argument(
        "the mesh's extent is zero or too large to represent (all vertices at one point, or coordinates beyond +-1e200)");
  // Clamped into the bounding box: a centroid rounded outside it (all x equal, far from the origin)
  // put the normalized mesh ~1e263 from the origin, and every later sum lost all precision.
  center_ = (sum / referenced).cwiseMax(lo).cwiseMin(hi);
  rest_.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v) rest_[v] = (input_[v] - center_) / scale_;
  X_ = rest_;

  compute_rest_quantities();
  progress.check();
  const int nF = static_cast<int>(topo_.faces.size());
  normal_star_.assign(nF, Vector3d::UnitZ());
  dual_.assign(nF, {0, 0, 0});
  face_mu_.assign(nF, 0.0);
  edge_star_.assign(topo_.edges.size(), Vector3d::Zero());
  face_cov_.assign(nF, Matrix3d::Zero());
  rotation_.assign(num_vertices, Matrix3d::Identity());
  rotation_q_.assign(num_vertices, Eigen::Quaterniond::Identity());
  corner_rhs_.resize(nF);
  component_sum_.resize(topo_.num_components);

  styles_.emplace_back(preset_style(settings::default_preset));
  face_style_.assign(nF, 0);
  apply_pins(pinned, pin_positions, progress);
  progress.finish();
}

void GaussSolver::compute_rest_quantities() {
  const int nF = static_cast<int>(topo_.faces.size());
  slot_weight_.resize(nF);
  slot_rest_.resize(nF);
  edge_weight_.assign(topo_.edges.size(), 0.0);
  for (int f = 0; f < nF; ++f) {
    const auto& t = topo_.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = rest_[t[(k + 1) % 3]] - rest_[t[k]];
    const double twice_area = e[0].cross(e[1]).norm();
    const double size = e[0].squaredNorm() + e[1].squaredNorm() + e[2].squaredNorm();
    const bool degenerate = !(twice_area > kDegenerateRatio * size);
    for (int k = 0; k < 3; ++k) {
      // Slot k's opposite corner is t[(k+2)%3]; its angle lies between -e[(k+2)%3] and e[(k+1)%3].
      const double cot = -e[(k + 2) % 3].dot(e[(k + 1) % 3]) / twice_area;
      const double w = degenerate ? kDegenerateWeight : 0.5 * cot;
      slot_weight_[f][k] = w;
      slot_rest_[f][k] = w * e[k];
      edge_weight_[topo_.face_edge[f][k]] += w;
    }
  }
  slot_edge_weight_.resize(nF);
  for (int f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) slot_edge_weight_[f][k] = edge_weight_[topo_.face_edge[f][k]];
}

void GaussSolver::set_styles(std::vector<PreferenceFunction> styles) {
  for (int s : face_style_)
    if (s >= static_cast<int>(styles.size())) {
      std::ostringstream msg;
      msg << "faces use style " << s << " but only " << styles.size()
          << " styles were given; assign face styles that fit the new list first";
      throw std::invalid_argument(msg.str());
    }
  styles_ = std::move(styles);
}

void GaussSolver::set_style(int index, PreferenceFunction style) {
  if (index < 0 || index >= num_styles()) {
    std::ostringstream msg;
    msg << "style index " << index << " is out of range (there are " << num_styles() << " styles)";
    throw std::invalid_argument(msg.str());
  }
  styles_[index] = std::move(style);
}

void GaussSolver::set_face_styles(const int64_t* style_of_input_face, int count) {
  if (count != num_input_faces_) {
    std::ostringstream msg;
    msg << "face styles must have one entry per face (" << num_input_faces_ << "), got " << count;
    throw std::invalid_argument(msg.str());
  }
  for (int i = 0; i < count; ++i)
    if (style_of_input_face[i] < -1 || style_of_input_face[i] >= num_styles()) {
      std::ostringstream msg;
      msg << "face " << i << " has style " << style_of_input_face[i] << "; valid: -1 (unstyled) to "
          << num_styles() - 1;
      throw std::invalid_argument(msg.str());
    }
  for (size_t f = 0; f < topo_.faces.size(); ++f)
    face_style_[f] = static_cast<int>(style_of_input_face[topo_.input_face[f]]);
}

void GaussSolver::set_lambda(double lambda) {
  settings::lambda.check(lambda);
  // Eq. 27: lambda only scales the right-hand side, so the factor stays valid.
  lambda_ = lambda;
}

void GaussSolver::set_admm_iterations(int n) {
  settings::admm_iterations.check(n);
  admm_iterations_ = n;
}

void GaussSolver::set_pins(const std::vector<int64_t>& pinned, const double* pin_positions, Progress* watcher) {
  Progress unwatched;
  Progress& progress = watcher ? *watcher : unwatched;
  progress.start(SetupPhase::ordering);
  apply_pins(pinned, pin_positions, progress);
  progress.finish();
}

void GaussSolver::apply_pins(const std::vector<int64_t>& pinned, const double* pin_positions, Progress& progress) {
  const int nV = topo_.num_vertices;
  std::vector<Vector3d> targets(pinned.size());
  std::vector<uint8_t> seen(nV, 0);
  for (size_t i = 0; i < pinned.size(); ++i) {
    const int64_t v = pinned[i];
    if (v < 0 || v >= nV) {
      std::ostringstream msg;
      msg << "pinned vertex index " << v << " is out of range (the mesh has " << nV << " vertices)";
      throw std::invalid_argument(msg.str());
    }
    if (seen[v]++) {
      std::ostringstream msg;
      msg << "vertex " << v << " is pinned more than once";
      throw std::invalid_argument(msg.str());
    }
    targets[i] = pin_positions ? Vector3d(pin_positions[3 * i], pin_positions[3 * i + 1], pin_positions[3 * i + 2])
                               : input_[new_of_old_[v]];
    if (!targets[i].allFinite()) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is NaN or infinite";
      throw std::invalid_argument(msg.str());
    }
    // Farther out, squared edge lengths overflow (~1e150 mesh sizes) and E_ARAP turns infinite.
    if (!((targets[i] - center_).cwiseAbs().maxCoeff() <= 1e12 * scale_)) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is too far from the mesh (more than 1e12 times its size)";
      throw std::invalid_argument(msg.str());
    }
  }
  // Strong guarantee: factor() fills these anew; if it throws (a cancelled or failed factorization,
  // which leaves cholesky_ as it was) the previous state comes back.
  auto state = std::tie(pinned_input_, pinned_, pin_targets_, component_free_, component_rest_center_,
                        component_size_, unknown_of_vertex_, vertex_of_unknown_, fixed_rhs_, rhs_);
  auto previous = std::make_tuple(std::move(pinned_input_), std::move(pinned_), std::move(pin_targets_),
                                  std::move(component_free_), std::move(component_rest_center_),
                                  std::move(component_size_), std::move(unknown_of_vertex_),
                                  std::move(vertex_of_unknown_), std::move(fixed_rhs_), std::move(rhs_));
  try {
    pinned_input_ = pinned;
    pinned_.resize(pinned.size());
    for (size_t i = 0; i < pinned.size(); ++i) pinned_[i] = new_of_old_[pinned[i]];
    pin_targets_ = std::move(targets);
    factor(progress);
  } catch (...) {
    state = std::move(previous);
    throw;
  }
  for (size_t i = 0; i < pinned_.size(); ++i) X_[pinned_[i]] = (pin_targets_[i] - center_) / scale_;
}

void GaussSolver::factor(Progress& progress) {
  const int nV = topo_.num_vertices;
  const int nC = topo_.num_components;
  // Fixed vertices: pins, plus one anchor per component without a pin (the ARAP system only
  // determines such a component up to a translation; the anchor removes that null space and the
  // component is re-centred on its rest centroid after every solve).
  std::vector<uint8_t> fixed(nV, 0);
  component_free_.assign(nC, 1);
  for (int64_t v : pinned_) {
    fixed[v] = 1;
    if (topo_.component[v] >= 0) component_free_[topo_.component[v]] = 0;
  }
  std::vector<uint8_t> anchored(nC, 0);
  component_rest_center_.assign(nC, Vector3d::Zero());
  component_size_.assign(nC, 0);
  for (int v = 0; v < nV; ++v) {
    const int c = topo_.component[v];
    if (c < 0) continue;
    component_rest_center_[c] += rest_[v];
    ++component_size_[c];
    if (component_free_[c] && !anchored[c]) anchored[c] = fixed[v] = 1;
  }
  for (int c = 0; c < nC; ++c) component_rest_center_[c] /= component_size_[c];

  unknown_of_vertex_.assign(nV, -1);
  vertex_of_unknown_.clear();
  for (int v = 0; v < nV; ++v)
    if (topo_.component[v] >= 0 && !fixed[v]) {
      unknown_of_vertex_[v] = static_cast<int>(vertex_of_unknown_.size());
      vertex_of_unknown_.push_back(v);
    }
  const int n = static_cast<int>(vertex_of_unknown_.size());
  // Fixed vertices sit at their pin target or (anchors) at the rest position.
  std::vector<Vector3d> fixed_pos(nV);
  for (int v = 0; v < nV; ++v) fixed_pos[v] = rest_[v];
  for (size_t i = 0; i < pinned_.size(); ++i) fixed_pos[pinned_[i]] = (pin_targets_[i] - center_) / scale_;

  // The lower triangle of L_ff, built column by column from the edge list (sorted by (lo, hi), and
  // the numbering of unknowns follows the vertices'), with the fixed neighbours moved to the rhs.
  std::vector<double> diagonal(n, 0.0);
  fixed_rhs_.assign(n, Vector3d::Zero());
  std::vector<int> col_count(n, 1);  // the diagonal
  for (size_t e = 0; e < topo_.edges.size(); ++e) {
    const int a = topo_.edges[e][0], b = topo_.edges[e][1];
    const int ua = unknown_of_vertex_[a], ub = unknown_of_vertex_[b];
    const double w = edge_weight_[e];
    if (ua >= 0) diagonal[ua] += w;
    if (ub >= 0) diagonal[ub] += w;
    if (ua >= 0 && ub >= 0) ++col_count[ua];  // ua < ub: entry (ub, ua) in column ua
    else if (ua >= 0) fixed_rhs_[ua] += w * fixed_pos[b];
    else if (ub >= 0) fixed_rhs_[ub] += w * fixed_pos[a];
  }
  rhs_.assign(3 * static_cast<size_t>(n), 0.0);  // before the factor: nothing may throw after it
  if (n > 0) {
    Eigen::SparseMatrix<double> A(n, n);
    A.reserve(col_count);
    for (int u = 0; u < n; ++u) A.insert(u, u) = diagonal[u];
    for (size_t e = 0; e < topo_.edges.size(); ++e) {
      const int ua = unknown_of_vertex_[topo_.edges[e][0]], ub = unknown_of_vertex_[topo_.edges[e][1]];
      if (ua >= 0 && ub >= 0) A.insert(ub, ua) = -edge_weight_[e];
    }
    A.makeCompressed();
    cholesky_.factor(A, &progress);
  }
  ++factorization_count_;
}

void GaussSolver::face_pass() {
  // Algorithm 1's initialization (n* = n_f, e* = e_ij, u = 0) fused with the first round's normal
  // update, which only needs this face's own edges: the first round reads no shared array.
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_;
  const double zero[3] = {0, 0, 0};
  parallel::for_each(nF, kParallelMin, [&](int f) {
    const auto& t = topo_.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = X_[t[(k + 1) % 3]] - X_[t[k]];
    const Vector3d c = e[0].cross(e[1]);
    const double len = c.norm();
    const double size = e[0].squaredNorm() + e[1].squaredNorm() + e[2].squaredNorm();
    const bool degenerate = !(len > 1e-12 * size) || !std::isfinite(len);
    const int s = face_style_[f];
    face_mu_[f] = (!degenerate && s >= 0) ? styles_[s].mu() : 0.0;
    dual_[f] = {0, 0, 0};
    if (face_mu_[f] > 0.0) {
      // The sign of e*_ij does not matter while u = 0 (both terms are even in e*).
      const double lw[3] = {lam * slot_edge_weight_[f][0], lam * slot_edge_weight_[f][1],
                            lam * slot_edge_weight_[f][2]};
      normal_star_[f] = newton_normal(styles_[s], c / len, e, lw, zero);
    }
    Matrix3d cov = e[0] * slot_rest_[f][0].transpose();
    cov.noalias() += e[1] * slot_rest_[f][1].transpose();
    cov.noalias() += e[2] * slot_rest_[f][2].transpose();
    face_cov_[f] = cov;
  });
}

void GaussSolver::fit_rotations() {
  const int nV = topo_.num_vertices;
  parallel::for_each(nV, kParallelMin, [&](int v) {
    const int begin = topo_.vertex_corner_start[v], end = topo_.vertex_corner_start[v + 1];
    if (begin == end) return;
    Matrix3d M = Matrix3d::Zero();
    for (int i = begin; i < end; ++i) M += face_cov_[topo_.vertex_corners[i] / 3];
    rotation_[v] = closest_rotation_warm(M, rotation_q_[v]);
  });
}

void GaussSolver::admm_round(bool first_round) {
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_;
  // Normals (Eqs. 17-22): the first round's update happened in face_pass(). Later rounds start with
  // the previous round's dual update (Eq. 25).
  if (!first_round) {
    parallel::for_each(nF, kParallelMin, [&](int f) {
      if (face_mu_[f] == 0.0) return;
      const Vector3d n = normal_star_[f];
      const auto& fe = topo_.face_edge[f];
      const Vector3d es[3] = {edge_star_[fe[0]], edge_star_[fe[1]], edge_star_[fe[2]]};
      for (int k = 0; k < 3; ++k) dual_[f][k] += es[k].dot(n);
      const double lw[3] = {lam * slot_edge_weight_[f][0], lam * slot_edge_weight_[f][1],
                            lam * slot_edge_weight_[f][2]};
      normal_star_[f] = newton_normal(styles_[face_style_[f]], n, es, lw, dual_[f].data());
    });
  }
  // Edges (Eq. 24): (I + sum mu n n^T) e* = e - sum mu u n over the styled faces of the edge.
  const int nE = static_cast<int>(topo_.edges.size());
  parallel::for_each(nE, kParallelMin, [&](int e) {
    const Vector3d cur = X_[topo_.edges[e][1]] - X_[topo_.edges[e][0]];
    // Collect the styled faces (usually one or two; more on non-manifold edges).
    int count = 0;
    double mu[2];
    const Vector3d* nrm[2];
    Matrix3d A = Matrix3d::Identity();
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
      A.noalias() += m * (n * n.transpose());
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
    } else {
      Vector3d x;
      edge_star_[e] = solve_symmetric3(A, b, x) ? x : cur;  // A >= I: always solvable
    }
  });
}

void GaussSolver::assemble_rhs() {
  const int nF = static_cast<int>(topo_.faces.size());
  const double lam = lambda_, inv = 1.0 / (1.0 + lambda_);
  parallel::for_each(nF, kParallelMin, [&](int f) {
    const auto& t = topo_.faces[f];
    // Spokes and rims: every vertex of the face rotates the face's three edges, so the ARAP target
    // of an edge is the mean rotation of the face applied to its rest vector (Eq. 27).
    const Matrix3d Rf = (rotation_[t[0]] + rotation_[t[1]] + rotation_[t[2]]) * (1.0 / 3.0);
    Vector3d d[3];
    for (int k = 0; k < 3; ++k) {
      const double s = topo_.face_edge_sign[f][k];
      d[k] = (Rf * slot_rest_[f][k] + (lam * slot_weight_[f][k] * s) * edge_star_[topo_.face_edge[f][k]]) * inv;
    }
    // Corner k is the head of slot k-1 and the tail of slot k.
    for (int k = 0; k < 3; ++k) corner_rhs_[f][k] = d[(k + 2) % 3] - d[k];
  });
  const int n = static_cast<int>(vertex_of_unknown_.size());
  parallel::for_each(n, kParallelMin, [&](int u) {
    const int v = vertex_of_unknown_[u];
    Vector3d b = fixed_rhs_[u];
    for (int i = topo_.vertex_corner_start[v]; i < topo_.vertex_corner_start[v + 1]; ++i) {
      const int c = topo_.vertex_corners[i];
      b += corner_rhs_[c / 3][c % 3];
    }
    double* r = &rhs_[3 * static_cast<size_t>(cholesky_.position(u))];  // elimination order
    r[0] = b.x();
    r[1] = b.y();
    r[2] = b.z();
  });
}

void GaussSolver::solve_and_recenter() {
  const int n = static_cast<int>(vertex_of_unknown_.size());
  if (n > 0) cholesky_.solve_ordered_in_place(rhs_.data());
  parallel::for_each(n, kParallelMin, [&](int u) {
    X_[vertex_of_unknown_[u]] = Vector3d(&rhs_[3 * static_cast<size_t>(cholesky_.position(u))]);
  });
  // Anchors went into the solve at their rest positions; translate each free component so that its
  // centroid stays where the rest pose had it.
  const int nV = topo_.num_vertices;
  std::fill(component_sum_.begin(), component_sum_.end(), Vector3d::Zero());
  for (int v = 0; v < nV; ++v) {
    const int c = topo_.component[v];
    if (c < 0 || !component_free_[c]) continue;
    if (unknown_of_vertex_[v] < 0) X_[v] = rest_[v];  // the anchor
    component_sum_[c] += X_[v];
  }
  parallel::for_each(nV, kParallelMin, [&](int v) {
    const int c = topo_.component[v];
    if (c < 0 || !component_free_[c]) return;
    X_[v] += component_rest_center_[c] - component_sum_[c] / component_size_[c];
  });
}

void GaussSolver::step() {
  const int threads = tuner_.next(parallel::max_threads());
  const parallel::ScopedThreads scoped(threads);
  const auto start = Clock::now();
  auto t0 = start;
  face_pass();
  timings_.faces = ms_since(t0);
  t0 = Clock::now();
  fit_rotations();
  timings_.rotations = ms_since(t0);
  t0 = Clock::now();
  // The last round's dual update is skipped: duals are re-initialized at the next step and the
  // global step does not read them.
  for (int r = 0; r < admm_iterations_; ++r) admm_round(r == 0);
  timings_.admm = ms_since(t0);
  t0 = Clock::now();
  assemble_rhs();
  timings_.rhs = ms_since(t0);
  t0 = Clock::now();
  solve_and_recenter();
  timings_.solve = ms_since(t0);
  ++step_count_;
  tuner_.record(threads, ms_since(start));
  timings_.threads = threads;
}

void GaussSolver::reset() {
  X_ = rest_;
  // The rotation warm start is state too: a reset run must repeat the first run bit for bit.
  std::fill(rotation_q_.begin(), rotation_q_.end(), Eigen::Quaterniond::Identity());
  for (size_t i = 0; i < pinned_.size(); ++i) X_[pinned_[i]] = (pin_targets_[i] - center_) / scale_;
  step_count_ = 0;
}

template <typename T>
void GaussSolver::write_vertices(T* out) const {
  const int nV = topo_.num_vertices;
  for (int old = 0; old < nV; ++old) {
    const int v = new_of_old_[old];
    const Vector3d p = topo_.component[v] >= 0 ? to_caller(X_[v]) : input_[v];
    out[3 * old] = static_cast<T>(p.x());
    out[3 * old + 1] = static_cast<T>(p.y());
    out[3 * old + 2] = static_cast<T>(p.z());
  }
  // Pins are returned exactly as given, not through the normalization round trip.
  for (size_t i = 0; i < pinned_input_.size(); ++i)
    for (int k = 0; k < 3; ++k) out[3 * pinned_input_[i] + k] = static_cast<T>(pin_targets_[i][k]);
}

void GaussSolver::copy_vertices(double* out) const { write_vertices(out); }
void GaussSolver::copy_vertices(float* out) const { write_vertices(out); }

double GaussSolver::arap_energy() const {
  // E_ARAP (Eqs. 1-2) with spokes-and-rims neighbourhoods and each vertex's optimal rotation for the
  // current mesh. A read-out, not on the step's path: it recomputes what it needs.
  const int nV = topo_.num_vertices;
  std::vector<double> per_vertex(nV, 0.0);
  parallel::for_each(nV, kParallelMin, [&](int v) {
    const int begin = topo_.vertex_corner_start[v], end = topo_.vertex_corner_start[v + 1];
    if (begin == end) return;
    Matrix3d M = Matrix3d::Zero();
    for (int i = begin; i < end; ++i) {
      const int f = topo_.vertex_corners[i] / 3;
      const auto& t = topo_.faces[f];
      for (int k = 0; k < 3; ++k) M += (X_[t[(k + 1) % 3]] - X_[t[k]]) * slot_rest_[f][k].transpose();
    }
    const Matrix3d R = closest_rotation(M);
    double sum = 0;
    for (int i = begin; i < end; ++i) {
      const int f = topo_.vertex_corners[i] / 3;
      const auto& t = topo_.faces[f];
      for (int k = 0; k < 3; ++k) {
        const Vector3d e = X_[t[(k + 1) % 3]] - X_[t[k]];
        const Vector3d eh = rest_[t[(k + 1) % 3]] - rest_[t[k]];
        sum += 0.5 * slot_weight_[f][k] * (e - R * eh).squaredNorm();
      }
    }
    per_vertex[v] = sum;
  });
  double total = 0;  // sequential sum: identical for any thread count
  for (double e : per_vertex) total += e;
  return total;
}

double GaussSolver::g_energy() const {
  double total = 0;
  for (size_t f = 0; f < topo_.faces.size(); ++f) {
    const int s = face_style_[f];
    if (s < 0) continue;
    const auto& t = topo_.faces[f];
    const Vector3d c = (X_[t[1]] - X_[t[0]]).cross(X_[t[2]] - X_[t[0]]);
    const double len = c.norm();
    if (!(len > 0) || !std::isfinite(len)) continue;
    total += styles_[s].value(c / len);
  }
  return total;
}

}  // namespace gauss
