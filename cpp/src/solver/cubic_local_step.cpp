#include "gauss/solver/cubic_local_step.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gauss/solver/closest_rotation.h"
#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// argmin_z k ||z||_1 + 1/2 ||z - x||^2, component-wise.
Vector3d soft_threshold(const Vector3d& x, double k) {
  Vector3d z;
  for (int i = 0; i < 3; ++i) z[i] = std::max(x[i] - k, 0.0) - std::max(-x[i] - k, 0.0);
  return z;
}

}  // namespace

CubicLocalStep::CubicLocalStep(const MeshTopology& topo, const std::vector<Vector3d>& rest,
                               const std::vector<double>& edge_weight,
                               const std::vector<std::array<double, 3>>& slot_weight) {
  const int nV = topo.num_vertices;
  const int nF = static_cast<int>(topo.faces.size());
  if (rest.size() != static_cast<size_t>(nV) || edge_weight.size() != topo.edges.size() ||
      slot_weight.size() != topo.faces.size())
    throw std::invalid_argument("CubicLocalStep: the sizes of the mesh, rest positions and weights disagree");
  slot_rest_.resize(nF);
  std::vector<Vector3d> face_normal(nF);  // twice the area times the unit normal
  for (int f = 0; f < nF; ++f) {
    const auto& t = topo.faces[f];
    for (int k = 0; k < 3; ++k)
      slot_rest_[f][k] = edge_weight[topo.face_edge[f][k]] * (rest[t[(k + 1) % 3]] - rest[t[k]]);
    face_normal[f] = (rest[t[1]] - rest[t[0]]).cross(rest[t[2]] - rest[t[0]]);
  }
  normal_.assign(nV, Vector3d::Zero());
  area_.assign(nV, 0.0);
  for (int v = 0; v < nV; ++v) {
    Vector3d sum = Vector3d::Zero();
    double twice_area = 0;
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const Vector3d& c = face_normal[topo.vertex_corners[i] / 3];
      sum += c;
      twice_area += c.norm();
    }
    area_[v] = twice_area / 6.0;  // a third of each face's area
    const double len = sum.norm();
    // Faces that cancel out (a folded sheet, a zero-area star) leave no direction to stylize.
    if (std::isfinite(len) && len > 1e-12 * twice_area && len > 1e-300) normal_[v] = sum / len;
  }
  build_global_rhs_stars(topo, rest, slot_weight);
  weight_.assign(nV, 0.0);
  frame_.assign(nV, 0);
  frames_.assign(1, Matrix3d::Identity());
  frame_is_identity_.assign(1, 1);
  carried_.resize(kCarriedPerVertex * static_cast<size_t>(nV));
  rho_.resize(nV);
  iterations_.resize(nV);
  reset();
}

void CubicLocalStep::build_global_rhs_stars(const MeshTopology& topo, const std::vector<Vector3d>& rest,
                                            const std::vector<std::array<double, 3>>& slot_weight) {
  const int nV = topo.num_vertices;
  const int nF = static_cast<int>(topo.faces.size());
  // Each face's corner vectors (w d^_prev - w d^_next) / 3, with the Laplacian's weights.
  std::vector<std::array<Vector3d, 3>> corner(nF);
  for (int f = 0; f < nF; ++f) {
    const auto& t = topo.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = rest[t[(k + 1) % 3]] - rest[t[k]];
    const std::array<double, 3>& w = slot_weight[f];
    // Corner k is the head of slot k-1 and the tail of slot k.
    for (int k = 0; k < 3; ++k) corner[f][k] = (w[(k + 2) % 3] * e[(k + 2) % 3] - w[k] * e[k]) / 3.0;
  }
  star_start_.assign(nV + 1, 0);
  star_.clear();
  star_.reserve(2 * topo.edges.size() + nV);
  std::vector<StarTerm> terms;  // one vertex's, before merging
  for (int v = 0; v < nV; ++v) {
    terms.clear();
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const int f = topo.vertex_corners[i] / 3, k = topo.vertex_corners[i] % 3;
      for (int j = 0; j < 3; ++j) terms.push_back({corner[f][k], topo.faces[f][j]});
    }
    std::sort(terms.begin(), terms.end(), [](const StarTerm& a, const StarTerm& b) { return a.vertex < b.vertex; });
    for (const StarTerm& term : terms) {
      if (static_cast<int>(star_.size()) > star_start_[v] && star_.back().vertex == term.vertex) star_.back().rest += term.rest;
      else star_.push_back(term);
    }
    star_start_[v + 1] = static_cast<int>(star_.size());
  }
}

int64_t CubicLocalStep::bytes_needed(int num_vertices, int num_faces) {
  // Per face: slot_rest_ 72, the constructor's temporaries (face normals 24, corner vectors 72), the
  // stars' terms 96 (32 bytes for each of about 3 per face: two per edge). Per vertex: normal_ 24,
  // area_ 8, weight_ 8, frame_ 4, carried_ 48, rho_ 8, iterations_ 4, star_start_ 4, its own term 32.
  return 264 * int64_t{num_faces} + 140 * int64_t{num_vertices};
}

void CubicLocalStep::set_vertex_styles(const std::vector<double>& strength, const std::vector<int>& frame,
                                       const std::vector<Matrix3d>& frames) {
  const size_t nV = normal_.size();
  if (strength.size() != nV || frame.size() != nV || frames.empty())
    throw std::invalid_argument("CubicLocalStep: one strength and one frame per vertex are needed");
  for (size_t v = 0; v < nV; ++v) {
    if (frame[v] < 0 || frame[v] >= static_cast<int>(frames.size()) || !(strength[v] >= 0))
      throw std::invalid_argument("CubicLocalStep: a vertex's frame index or strength is out of range");
    weight_[v] = normal_[v].isZero() ? 0.0 : area_[v] * strength[v];
    // The warm start stays meaningful across a change of orientation: the same world vectors.
    const Matrix3d change = frames[frame[v]].transpose() * frames_[frame_[v]];
    carried_[2 * v] = change * carried_[2 * v];
    carried_[2 * v + 1] = change * carried_[2 * v + 1];
  }
  frame_ = frame;
  frames_ = frames;
  frame_is_identity_.assign(frames.size(), 0);
  for (size_t i = 0; i < frames.size(); ++i) frame_is_identity_[i] = frames[i] == Matrix3d::Identity();
}

void CubicLocalStep::reset() {
  for (size_t v = 0; v < normal_.size(); ++v) {
    carried_[2 * v] = frames_[frame_[v]].transpose() * normal_[v];
    carried_[2 * v + 1].setZero();
    rho_[v] = area_[v] > 0 ? std::min(cubic_admm::kRhoPerArea * area_[v], cubic_admm::kRhoInit) : cubic_admm::kRhoInit;
    iterations_[v] = 0;
  }
}

void CubicLocalStep::covariances(const MeshTopology& topo, const std::vector<Vector3d>& X,
                                 std::vector<Matrix3d>& face_cov) const {
  const int nF = static_cast<int>(topo.faces.size());
  parallel::for_each(nF, parallel::kMinParallelItems, [&](int f) {
    const auto& t = topo.faces[f];
    Matrix3d c = (X[t[1]] - X[t[0]]) * slot_rest_[f][0].transpose();
    c.noalias() += (X[t[2]] - X[t[1]]) * slot_rest_[f][1].transpose();
    c.noalias() += (X[t[0]] - X[t[2]]) * slot_rest_[f][2].transpose();
    face_cov[f] = c;
  });
}

void CubicLocalStep::fit(const MeshTopology& topo, const std::vector<Matrix3d>& face_cov, double lambda,
                         bool extrapolated, std::vector<Matrix3d>& rotation, std::vector<Eigen::Quaterniond>& rotation_q,
                         const Matrix3d* prior) {
  using namespace cubic_admm;
  const double sqrt6_abs = std::sqrt(6.0) * kAbsTol, sqrt3_abs = std::sqrt(3.0) * kAbsTol;
  const int nV = topo.num_vertices;
  // One vertex's ADMM, as state, so that two vertices advance in lockstep and their rotation fits run
  // side by side (closest_rotation_warm_lanes: the same bits as one after another, in 0.78 of the
  // time). Each vertex's arithmetic is exactly what it would be alone.
  struct Lane {
    int v = -1;
    bool admm = false;     // false: no cubic term, ARAP's rotation (one fit)
    bool fitting = false;  // another rotation fit to run
    Matrix3d M;
    Vector3d z, u;
    double rho = 0, w = 0;
    int it = 0;
  };
  // A pair's ADMM costs several times a typical loop item, so fewer pairs already pay for a fork.
  parallel::for_each((nV + 1) / 2, parallel::kMinParallelItems / 8, [&](int pair) {
    Lane lane[2];
    // Lane l's rotation fit: its matrix, its start (q and its rotation matrix), then its result.
    Matrix3d target[2], R[2];
    Eigen::Quaterniond q[2];
    for (int l = 0; l < 2; ++l) {
      Lane& a = lane[l];
      const int v = 2 * pair + l;
      if (v >= nV) continue;
      const int begin = topo.vertex_corner_start[v], end = topo.vertex_corner_start[v + 1];
      if (begin == end) continue;
      a.v = v;
      a.M = face_cov[topo.vertex_corners[begin] / 3];
      for (int i = begin + 1; i < end; ++i) a.M += face_cov[topo.vertex_corners[i] / 3];
      if (prior) a.M += prior[v];
      a.w = lambda * weight_[v];
      a.admm = a.w > 0;
      a.fitting = true;
      // The rotation fit's start, carried from one ADMM iteration to the next (closest_rotation.h).
      q[l] = rotation_q[v];
      R[l] = q[l].toRotationMatrix();
      if (!a.admm) {  // no cubic term: ARAP's rotation, exactly
        target[l] = a.M;
        continue;
      }
      a.rho = rho_[v];
      a.z = carried_[2 * v];
      a.u = carried_[2 * v + 1] / a.rho;
    }
    while (lane[0].fitting || lane[1].fitting) {
      for (int l = 0; l < 2; ++l) {
        Lane& a = lane[l];
        if (!a.fitting || !a.admm) continue;
        ++a.it;
        // R: min ARAP + rho/2 ||R n - Q (z - u)||^2, i.e. the closest rotation to M + rho Q (z - u) n^T.
        const int f = frame_[a.v];
        const Vector3d t = frame_is_identity_[f] ? Vector3d(a.z - a.u) : Vector3d(frames_[f] * (a.z - a.u));
        // target = M + (rho t) n^T, coefficient by coefficient (Eigen's expression went through
        // misaligned stack temporaries here).
        const Vector3d rt = a.rho * t;
        const Vector3d& n = normal_[a.v];
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r) target[l](r, c) = a.M(r, c) + rt[r] * n[c];
      }
      const bool active[2] = {lane[0].fitting, lane[1].fitting};
      closest_rotation_warm_lanes<2>(target, q, R, active);
      for (int l = 0; l < 2; ++l) {
        Lane& a = lane[l];
        if (!a.fitting) continue;
        if (!a.admm) {
          a.fitting = false;
          continue;
        }
        const int f = frame_[a.v];
        const bool turned = !frame_is_identity_[f];  // most vertices: an unrotated cube
        const Vector3d Rn = R[l] * normal_[a.v];
        const Vector3d y = turned ? Vector3d(frames_[f].transpose() * Rn) : Rn;
        const Vector3d z_old = a.z;
        a.z = soft_threshold(y + a.u, a.w / a.rho);
        a.u += y - a.z;
        // Residuals squared: the tests below compare them squared, saving this loop three of its five
        // square roots.
        const double primal2 = (a.z - y).squaredNorm(), dual2 = a.rho * a.rho * (a.z - z_old).squaredNorm();
        // The reference's stopping rule (rho u is the same before and after a rescaling below). Unlike
        // the reference, rho is not rebalanced on the iteration that stops: there both residuals are
        // rounding-level noise, and rescaling by their ratio, step after step, put vertices into limit
        // cycles (rho up, up, down, down) that kept reldV from falling below 1e-3.
        const double eps_primal = sqrt6_abs + kRelTol * std::sqrt(std::max(y.squaredNorm(), a.z.squaredNorm()));
        const double eps_dual = sqrt3_abs + kRelTol * a.rho * a.u.norm();
        if (primal2 < eps_primal * eps_primal && dual2 < eps_dual * eps_dual) {
          a.fitting = false;
          continue;
        }
        // At an extrapolated state the first iteration's primal residual measures the extrapolation
        // (z was pushed ahead of R n): balancing rho on it would raise rho and slow the cubic term's pull
        // until the run stops short of the plain result (docs/performance.md#converging-in-fewer-steps).
        if (!(a.it == 1 && extrapolated)) {
          if (primal2 > kMu * kMu * dual2 && a.rho * kTau <= kMaxRho) {
            a.rho *= kTau;
            a.u /= kTau;
          } else if (dual2 > kMu * kMu * primal2 && a.rho / kTau >= kMinRho) {
            a.rho /= kTau;
            a.u *= kTau;
          }
        }
        // Out of iterations: the vertex keeps its last iterate.
        if (a.it >= kMaxIterations) a.fitting = false;
      }
    }
    for (int l = 0; l < 2; ++l) {
      const Lane& a = lane[l];
      if (a.v < 0) continue;
      rotation_q[a.v] = q[l];
      rotation[a.v] = R[l];
      iterations_[a.v] = a.it;
      if (!a.admm) continue;
      carried_[2 * a.v] = a.z;
      carried_[2 * a.v + 1] = a.rho * a.u;
      rho_[a.v] = a.rho;
    }
  });
}

long long CubicLocalStep::last_admm_iterations() const {
  long long total = 0;
  for (int it : iterations_) total += it;
  return total;
}

double CubicLocalStep::cubic_energy(double lambda, const std::vector<Matrix3d>& rotation) const {
  double total = 0;  // sequential: the same for any thread count
  for (size_t v = 0; v < normal_.size(); ++v)
    if (weight_[v] > 0) total += lambda * weight_[v] * (frames_[frame_[v]].transpose() * (rotation[v] * normal_[v])).lpNorm<1>();
  return total;
}

}  // namespace gauss
