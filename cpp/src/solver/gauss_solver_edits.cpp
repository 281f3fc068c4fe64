// GaussSolver between steps: parameters, pins and the current vertices (styles: gauss_solver_styles.cpp).
// Everything here takes effect at the next step; only set_pins() re-factors (see constrained_laplacian.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gauss/solver/gauss_solver.h"
#include "gauss/util/memory_budget.h"
#include "gauss/settings.h"

namespace gauss {

using Eigen::Vector3d;

void GaussSolver::set_lambda(double lambda) {
  settings::lambda.check(lambda);
  // Eq. 27: lambda only scales the right-hand side, so the factor stays valid.
  lambda_ = lambda;
  iteration_.invalidate();
}

void GaussSolver::set_admm_iterations(int n) {
  settings::admm_iterations.check(n);
  admm_iterations_ = n;
  iteration_.invalidate();
}

void GaussSolver::set_keep_volume(bool on) {
  keep_volume_ = on;
  iteration_.invalidate();
}

void GaussSolver::set_resolution_independent(bool on) {
  if (on == resolution_independent_) return;
  resolution_independent_ = on;
  update_face_coupling();
  iteration_.invalidate();
}

void GaussSolver::set_weigh_finer_faces(bool on) {
  if (on == weigh_finer_faces_) return;
  weigh_finer_faces_ = on;
  // Only the Gauss method's normal step reads the rule, and only with the setting on.
  if (resolution_independent_ && method_ == Method::gauss) iteration_.invalidate();
}

void GaussSolver::set_paper_step_any_sigma(bool on) {
  if (on == paper_step_any_sigma_) return;
  paper_step_any_sigma_ = on;
  if (method_ == Method::gauss) iteration_.invalidate();
}

void GaussSolver::set_square_flat_regions(bool on) {
  if (on == square_flat_regions_) return;
  square_flat_regions_ = on;
  update_square_prior();
  iteration_.invalidate();
}

void GaussSolver::set_reference_face_area(double area) {
  if (!(area > 0.0 && std::isfinite(area))) throw std::invalid_argument("reference face area must be positive");
  if (area == reference_face_area_) return;
  reference_face_area_ = area;
  update_face_coupling();
  iteration_.invalidate();
}

void GaussSolver::set_lean_steps(bool lean) {
  const int nF = static_cast<int>(topo_.faces.size());
  if (lean) {
    slot_rest_ = {};
    slot_edge_weight_ = {};
    if (!cubic_ready_) face_scratch_ = {};
    return;
  }
  if (!lean_steps()) return;
  // Filled from the lean accessors: the same values they compute.
  std::vector<std::array<Eigen::Vector3d, 3>> rest(nF);
  std::vector<std::array<double, 3>> edge(nF);
  for (int f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) rest[f][k] = slot_rest(f, k), edge[f][k] = slot_edge_weight(f, k);
  slot_rest_ = std::move(rest);
  slot_edge_weight_ = std::move(edge);
  if (face_scratch_.empty()) face_scratch_.assign(nF, Eigen::Matrix3d::Zero());
}

void GaussSolver::set_method(Method method) {
  if (method != Method::gauss && method != Method::cubic) throw std::invalid_argument("unknown stylization method");
  if (method == Method::cubic && !cubic_ready_) {
    const size_t carried = CubicLocalStep::kCarriedPerVertex * static_cast<size_t>(topo_.num_vertices);
    const int nF = static_cast<int>(topo_.faces.size());
    check_memory(CubicLocalStep::bytes_needed(topo_.num_vertices, nF) + FixedPointIteration::carried_bytes(carried) +
                     static_cast<int64_t>(sizeof(Eigen::Matrix3d)) * nF,
                 "the cubic method's data for " + std::to_string(topo_.num_vertices) + " vertices");
    cubic_ = CubicLocalStep(topo_, rest_, edge_weight_, slot_weight_);
    face_scratch_.assign(nF, Eigen::Matrix3d::Zero());
    iteration_.prepare_carried(carried);
    cubic_ready_ = true;
    update_cubic_styles();
  }
  method_ = method;
  set_acceleration(acceleration());  // the method's momentum
  iteration_.invalidate();
}

void GaussSolver::set_acceleration(bool on) {
  iteration_.set_acceleration(on, method_ == Method::cubic ? settings::cubic_momentum : settings::gauss_momentum);
}

void GaussSolver::set_cubic_lambda(double lambda) {
  settings::cubic_lambda.check(lambda);
  cubic_lambda_ = lambda;
  iteration_.invalidate();
}

std::vector<Vector3d> GaussSolver::checked_pin_targets(const std::vector<int64_t>& pinned,
                                                       const double* positions) const {
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
    targets[i] = positions ? Vector3d(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
                           : input_[new_of_old_[v]];
    if (!targets[i].allFinite()) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is NaN or infinite";
      throw std::invalid_argument(msg.str());
    }
    if (!((targets[i] - center_).cwiseAbs().maxCoeff() <= settings::max_pin_distance * scale_)) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is too far from the mesh (more than "
          << settings::max_pin_distance << " times its size)";
      throw std::invalid_argument(msg.str());
    }
  }
  return targets;
}

std::vector<Vector3d> GaussSolver::to_solver_frame(const std::vector<Vector3d>& caller) const {
  std::vector<Vector3d> out(caller.size());
  for (size_t i = 0; i < caller.size(); ++i) out[i] = (caller[i] - center_) / scale_;
  return out;
}

void GaussSolver::set_pins(const std::vector<int64_t>& pinned, const double* pin_positions, Progress* watcher) {
  Progress unwatched;
  Progress& progress = watcher ? *watcher : unwatched;
  progress.start(SetupPhase::ordering);
  apply_pins(pinned, pin_positions, progress);
  progress.finish();
}

void GaussSolver::apply_pins(const std::vector<int64_t>& pinned, const double* pin_positions, Progress& progress) {
  std::vector<Vector3d> targets = checked_pin_targets(pinned, pin_positions);
  std::vector<int64_t> internal(pinned.size());
  for (size_t i = 0; i < pinned.size(); ++i) internal[i] = new_of_old_[pinned[i]];
  // Built aside and then moved in: if the factorization throws (Cancelled, OutOfMemory, not positive
  // definite), the solver keeps its previous pins and factor.
  laplacian_ = ConstrainedLaplacian(topo_, edge_weight_, rest_, internal, to_solver_frame(targets), &progress);
  ++factorization_count_;
  springs_.clear();  // their unknowns were the old system's
  volume_ = VolumeKeeper(topo_, rest_, internal);
  pinned_input_ = pinned;
  pin_targets_ = std::move(targets);
  place_pins_guarded();
  iteration_.invalidate();
}

void GaussSolver::set_pin_positions(const double* pin_positions, int count) {
  if (count != static_cast<int>(pinned_input_.size()) || (count > 0 && pin_positions == nullptr)) {
    std::ostringstream msg;
    msg << "pin positions must have one row per pinned vertex (" << pinned_input_.size() << "), got " << count;
    throw std::invalid_argument(msg.str());
  }
  std::vector<Vector3d> targets = checked_pin_targets(pinned_input_, pin_positions);
  laplacian_.set_pin_positions(to_solver_frame(targets));
  pin_targets_ = std::move(targets);
  place_pins_guarded();
  iteration_.invalidate();
}

void GaussSolver::place_pins_guarded() {
  if (guard_) {
    safe_ = X_;
    laplacian_.place_pins(X_);
    guard_->limit(safe_, X_);
  } else {
    laplacian_.place_pins(X_);
  }
  update_reach();
}

void GaussSolver::set_avoid_self_intersections(bool on) {
  if (on == avoid_self_intersections()) return;
  if (on) {
    const int64_t nV = topo_.num_vertices, nF = static_cast<int64_t>(topo_.faces.size());
    check_memory(SelfIntersectionGuard::bytes_needed(nV, nF) + 24 * nV + ContactSprings::bytes_needed(nV),
                 "the self-intersection guard for " + std::to_string(nV) + " vertices");
    // Made whole before it is kept: a start that runs out of memory leaves the solver unguarded, not
    // guarded from half a start.
    auto guard = std::make_unique<SelfIntersectionGuard>(topo_, rest_);
    guard->start_from(X_);
    safe_.resize(topo_.num_vertices);
    guard_ = std::move(guard);
  } else {
    guard_.reset();
    std::vector<Vector3d>().swap(safe_);
  }
  springs_.clear();
  iteration_.invalidate();
}

void GaussSolver::set_contact_stiffness(double stiffness) {
  if (!(stiffness >= 0 && std::isfinite(stiffness)))
    throw std::invalid_argument("the contact stiffness must be >= 0 and finite");
  springs_.set_stiffness(stiffness);
  if (stiffness == 0) springs_.clear();
  iteration_.invalidate();
}

void GaussSolver::set_vertices(const double* V, int count) {
  const int nV = topo_.num_vertices;
  if (count != nV || V == nullptr) {
    std::ostringstream msg;
    msg << "vertices must have one row per vertex (" << nV << "), got " << count;
    throw std::invalid_argument(msg.str());
  }
  for (int old = 0; old < nV; ++old) {  // all checks first: a refused call changes nothing
    const Vector3d p(V[3 * old], V[3 * old + 1], V[3 * old + 2]);
    if (!p.allFinite()) {
      std::ostringstream msg;
      msg << "vertex " << old << " has a NaN or infinite coordinate";
      throw std::invalid_argument(msg.str());
    }
    if (topo_.component[new_of_old_[old]] >= 0 &&
        !((p - center_).cwiseAbs().maxCoeff() <= settings::max_pin_distance * scale_)) {
      std::ostringstream msg;
      msg << "vertex " << old << " is too far from the mesh (more than " << settings::max_pin_distance
          << " times its size)";
      throw std::invalid_argument(msg.str());
    }
  }
  for (int old = 0; old < nV; ++old) {
    const int v = new_of_old_[old];
    if (topo_.component[v] >= 0) X_[v] = (Vector3d(V[3 * old], V[3 * old + 1], V[3 * old + 2]) - center_) / scale_;
  }
  laplacian_.place_pins(X_);
  update_reach();
  if (guard_) guard_->start_from(X_);  // the caller's vertices are the new start, contacts and all
  springs_.clear();
  if (resolution_independent_) {
    fit_rotations_of_start();
  } else {
    std::fill(rotation_q_.begin(), rotation_q_.end(), Eigen::Quaterniond::Identity());
    std::fill(rotation_.begin(), rotation_.end(), Eigen::Matrix3d::Identity());
  }
  if (cubic_ready_) cubic_.reset();  // the cubic method's ADMM warm start, as reset() clears it
  iteration_.invalidate();
}

}  // namespace gauss
